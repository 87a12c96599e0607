#include "pipeline/remesh_mesh.h"

#include <algorithm>
#include <cmath>

#include "common/errors.h"
#include "param/seams.h"
#include "pipeline/retry_until_valid.h"

namespace quadcover {

namespace {

/// The signed parameter area is the number of quads the map can hold; below a few there is nothing to extract
/// (too coarse a density, or a map folded onto itself by a field without branch points, e.g. a flat fan).
void check_extractable(const Mesh& mesh, const Parameterization& map) {
  const double area = flipped_triangles(mesh, map.uv).parameter_area;
  if (area >= 4) return;
  const long quads = std::lround(std::max(0.0, area));
  throw DensityTooCoarse("the map holds about " + std::to_string(quads) +
                         " quads, too few to extract a quad mesh; ask for more quads or a smaller edge length" +
                         (map.branch_points.empty() && mesh.num_boundary_loops() > 0
                              ? " (if the map folds onto itself, the field's singularities are whole turns)"
                              : ""));
}

RemeshJob remesh_once(const Mesh& input, const PipelineOptions& options, ProgressSink& progress) {
  RemeshJob job;
  // Without a requested count of 4 or more (the density stage would move the area to it), the first map's area
  // is the final one: too coarse a density is refused before the later stages.
  const bool area_is_final = options.param.density.target_quads < 4;
  job.param = parameterize_once(input, options, progress, area_is_final ? FirstMapCheck(check_extractable) : nullptr);
  StageMeter meter;
  auto lap = [&](const char* stage) { meter.lap(stage, job.param.seconds, job.param.peak_bytes); };
  FinishingProgress finishing(progress);  // extraction and smoothing run to the end, also after a Ctrl-C
  auto extract = [&] {
    check_extractable(job.param.mesh(input), job.param.map);
    job.extraction = extract_quads(job.param.mesh(input), job.param.map, options.extraction, finishing);
    lap("extract");
  };
  extract();
  if (job.extraction.mesh.num_faces() == 0 && job.param.fold_refinement.kept_rounds > 0) {
    // The refined map gave no quad mesh (seen on triangulations too coarse for the density): the map of the
    // input's own triangulation, folds and all, is the better result; said on stderr.
    PipelineOptions unrefined = options;
    unrefined.fold_refinement_rounds = 0;
    const int added = job.param.fold_refinement.added_faces;
    job.param = parameterize_once(input, unrefined, finishing);
    job.param.warnings.push_back("the fold-refined map (" + std::to_string(added) +
                                 " triangles added) gave no quad mesh; remeshed from the map without the fold "
                                 "refinement instead, which keeps its flipped or collapsed triangles");
    meter.restart();
    extract();
  }
  if (job.extraction.mesh.num_faces() == 0)
    throw NumericalError("remesh", "the extraction produced no faces (the map is broken)");
  const Mesh& mesh = job.param.mesh(input);  // the map's triangulation (refined, or the input)
  const Parameterization& map = job.param.map;
  QuadSmoothingOptions smoothing = options.smoothing;
  smoothing.features = options.param.features;  // the creases the field followed
  job.smoothing = smooth_quads(job.extraction.mesh, mesh, map, smoothing, finishing);
  lap("smooth");
  if (job.smoothing.iterations < options.smoothing.iterations && finishing.skip_improvements())
    record_cut_short(job.param, "quad smoothing");
  job.surface = check_surface(mesh, job.extraction.mesh.num_vertices(), job.extraction.mesh.faces);
  locate_surface_problems(job.extraction.mesh.V, job.extraction.mesh.faces, job.surface);
  for (std::string& w : remesh_warnings(job.surface, job.extraction.report)) job.param.warnings.push_back(std::move(w));
  job.boundary_loops =
      check_boundary_loops(mesh, input.num_vertices(), map, job.extraction.mesh, options.param.alignment);
  for (std::string& w : boundary_loop_warnings(job.boundary_loops)) job.param.warnings.push_back(std::move(w));
  lap("surface_check");
  return job;
}

Validity remesh_validity(const Mesh& input, const RemeshJob& job) {
  Validity v = map_validity(job.param.mesh(input), job.param.map);
  v.topology_changes = job.surface.same_topology ? 0 : 1;
  v.non_quads = job.surface.output.non_quads;
  return v;
}

}  // namespace

RemeshJob remesh_mesh(const Mesh& input, const PipelineOptions& options, ProgressSink& progress) {
  return retry_until_valid(
      options, [&](const PipelineOptions& o) { return remesh_once(input, o, progress); },
      [&](const RemeshJob& job) { return remesh_validity(input, job); }, progress);
}

}  // namespace quadcover
