// `quadcover metrics FILE... [--ref TRI.obj] [--json]`: the thesis's quality numbers for a parameterized OBJ
// (per-corner vt: ARAP (6.1.1), flips, cones, seamlessness, and the quad mesh its integer iso-lines extract to) or
// for a quad/polygon mesh (Table 7.1: RSD of edge lengths and corner angles, valences, non-quads), optionally
// with the surface distance to a reference triangle mesh.
#include <nlohmann/json.hpp>

#include "cli/common.h"
#include "cli/registry.h"
#include "common/errors.h"
#include "io/read_mesh.h"
#include "mesh/surface_counts.h"
#include "metrics/feature_fidelity.h"
#include "metrics/report.h"
#include "quad/extract_quads.h"
#include "quad/transitions.h"

namespace quadcover::cli {

namespace {

struct MetricsOptions {
  std::vector<std::string> inputs;
  std::string ref;
  std::string report;
  bool no_extract = false;
};

bool all_triangles(const PolygonSoup& soup) {
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    if (soup.face_size(f) != 3) return false;
  return soup.num_faces() > 0;
}

// Per-corner φ of the built mesh from the soup's vt references.
Eigen::MatrixX3cd corner_uv(const PolygonSoup& soup, const MeshBuildResult& built) {
  const Mesh& mesh = built.mesh;
  Eigen::MatrixX3cd uv(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const std::size_t sf = static_cast<std::size_t>(built.face_source[f]);
    for (int c = 0; c < 3; ++c) {
      long idx = -1;
      for (std::size_t j = 0; j < soup.face_size(sf); ++j)
        if (built.vertex_map[soup.face_begin(sf)[j]] == mesh.F()(f, c))
          idx = static_cast<long>(soup.face_uv[soup.face_offsets[sf] + j]);
      if (idx < 0 || idx >= soup.uv.rows())
        throw InputError(soup.file, soup.face_lines.empty() ? 0 : soup.face_lines[sf],
                         "a face corner has no texture coordinate (vt): cannot measure the parameterization");
      uv(f, c) = Complex(soup.uv(idx, 0), soup.uv(idx, 1));
    }
  }
  return uv;
}

nlohmann::json summary(const Report& r) {
  nlohmann::json j;
  if (r.parameterization) {
    j["arap"] = r.parameterization->arap;
    j["flipped_triangles"] = r.parameterization->flipped_triangles;
    j["branch_points"] = r.parameterization->branch_points;
    j["max_transition_error"] = r.parameterization->max_transition_error;
  }
  if (r.quad_mesh) {
    j["vertices"] = r.quad_mesh->vertices;
    j["faces"] = r.quad_mesh->faces;
    j["non_quads"] = r.quad_mesh->non_quads;
    j["rsd_edge_length"] = r.quad_mesh->rsd_edge_length;
    j["rsd_corner_angle"] = r.quad_mesh->rsd_corner_angle;
    j["irregular_vertices"] = r.quad_mesh->irregular_vertices;
    // Topology as `info` and the reports count it (mesh/surface_counts.h).
    const nlohmann::json topology = to_json(r.quad_mesh->topology);
    for (const char* key :
         {"components", "boundary_loops", "genus", "euler_characteristic", "manifold", "oriented", "closed"})
      j[key] = topology[key];
  }
  if (r.surface_distance) {
    j["distance_mean"] = r.surface_distance->mean;
    j["distance_max"] = r.surface_distance->max;
  }
  return j;
}

nlohmann::json run_metrics(const std::string& input, const std::string& report_path, const MetricsOptions& opt,
                           bool full_json) {
  const PolygonSoup soup = read_mesh(input);
  Report report;
  report.input = input;
  std::optional<Mesh> ref;
  if (!opt.ref.empty()) ref = build_mesh(read_mesh(opt.ref)).mesh;
  std::optional<FeatureFidelity> fidelity;
  if (soup.has_uv() && all_triangles(soup)) {
    const MeshBuildResult built = build_mesh(soup);
    const Mesh& mesh = built.mesh;
    const Parameterization P = parameterization_from_uv(mesh, corner_uv(soup, built));
    report.parameterization = param_quality(mesh, P);
    if (!opt.no_extract) {
      const ExtractionResult ex = extract_quads(mesh, P);
      report.extraction = ex.report;
      report.quad_mesh = quad_quality(ex.mesh);
      const Mesh& target = ref ? *ref : mesh;
      if (ex.mesh.num_faces() > 0)
        report.surface_distance = surface_distance(ex.mesh.V, ex.mesh.faces, target.V(), target.F());
      if (ref && ex.mesh.num_faces() > 0) fidelity = feature_fidelity(*ref, ex.mesh.V, ex.mesh.faces);
    }
  } else {
    const std::vector<std::vector<int>> faces = soup_polygons(soup);
    report.quad_mesh = quad_quality(soup.positions, faces);
    if (ref) report.surface_distance = surface_distance(soup.positions, faces, ref->V(), ref->F());
    if (ref && !faces.empty()) fidelity = feature_fidelity(*ref, soup.positions, faces);
  }
  nlohmann::json full = to_json(report), brief = summary(report);
  if (fidelity) {  // the reference's boundary and sharp edges against the output edges
    full["feature_fidelity"] = feature_fidelity_to_json(*fidelity);
    brief["features_covered_percent"] = full["feature_fidelity"]["total"]["covered_percent"];
    brief["features_p95"] = full["feature_fidelity"]["total"]["p95"];
  }
  if (!report_path.empty()) write_json_atomically(report_path, full);
  return full_json ? full : brief;
}

void register_metrics(CLI::App* cmd, GlobalOptions& global, int& exit_code) {
  auto opt = std::make_shared<MetricsOptions>();
  add_input_option(*cmd, opt->inputs, "Parameterized OBJ (triangles with vt) or polygon mesh files, or folders");
  cmd->add_option("--ref", opt->ref, "Reference triangle mesh for the surface distance and the feature fidelity")
      ->check(CLI::ExistingFile);
  cmd->add_option("--report", opt->report, "Write the full JSON report (one input) or a folder for NAME.metrics.json");
  cmd->add_flag("--no-extract", opt->no_extract, "Parameterized input: do not extract and measure the quad mesh");
  add_global_options(*cmd, global);
  run_on_inputs(*cmd, global, exit_code, opt->inputs,
                {"faces", "non_quads", "rsd_edge_length", "rsd_corner_angle", "irregular_vertices", "arap"},
                [opt, &global](const std::string& input, bool batch, ProgressSink&) {
                  const bool full = global.json && !batch;
                  return run_metrics(input, optional_output_path(input, opt->report, batch, ".metrics.json"), *opt,
                                     full);
                });
}

const CommandRegistrar registrar{
    70, "metrics", register_metrics,
    "Quality numbers of a parameterized OBJ (per-corner vt: normalized ARAP, flips, cones, seamlessness, and the "
    "extracted quad mesh) or of a quad mesh (RSD of edge lengths and angles, valences, non-quads, Table 7.1)"};

}  // namespace

}  // namespace quadcover::cli
