#include "pipeline/validity_retries.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "field/indices.h"
#include "param/ring_winding.h"
#include "param/seams.h"

namespace quadcover {

std::vector<int> wrong_winding_vertices(const Mesh& mesh, const Parameterization& map) {
  const Eigen::VectorXi target = quarter_index_of(mesh.num_vertices(), map.branch_points);
  const Eigen::VectorXi wound = map_quarter_index(mesh, map.uv);
  std::vector<int> out;
  for (int p = 0; p < mesh.num_vertices(); ++p)
    if (!mesh.is_boundary_vertex(p) && wound[p] != target[p]) out.push_back(p);
  return out;
}

Validity map_validity(const Mesh& mesh, const Parameterization& map) {
  Validity v;
  v.non_positive = flipped_triangles(mesh, map.uv).non_positive;
  v.wrong_windings = static_cast<int>(wrong_winding_vertices(mesh, map).size());
  return v;
}

double map_quads(const Parameterization& map) {
  double area = 0;
  for (Eigen::Index f = 0; f < map.uv.rows(); ++f) area += signed_uv_area(map.uv, f);
  return area;
}

double attempt_quads_factor(int k, const DensityOptions& given) {
  const bool requested = given.target_quads > 0 || given.edge_length > 0;
  return 1 + (requested ? 0.02 : 0.04) * ((k + 1) / 2) * (k % 2 == 1 ? 1 : -1);
}

PipelineOptions attempt_options(const PipelineOptions& given, double first_edge_length, int k) {
  PipelineOptions o = given;
  o.validity_retries = 0;
  const double factor = attempt_quads_factor(k, given.param.density);
  if (o.param.density.target_quads > 0)
    o.param.density.target_quads = std::max(1, static_cast<int>(std::lround(o.param.density.target_quads * factor)));
  else
    o.param.density.edge_length = first_edge_length / std::sqrt(factor);
  o.param.density.edge_length_from_default = given.param.density.edge_length <= 0;
  return o;
}

namespace {

std::string describe(const Validity& v) {
  std::string s = std::to_string(v.non_positive) + " non-positive triangles, " + std::to_string(v.wrong_windings) +
                  " vertices wound other than the field";
  if (v.topology_changes > 0) s += ", the quad mesh's topology changed";
  return s;
}

std::string percent(double factor) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.0f%%", 100 * (factor - 1));
  return buf;
}

}  // namespace

std::string validity_warning(const std::vector<ValidityAttempt>& attempts, int used) {
  const ValidityAttempt& kept = attempts[static_cast<std::size_t>(used)];
  if (attempts.size() == 1)
    return "the result is not valid: " + describe(kept.validity) +
           (kept.validity.worth_retrying() ? " (retries off)" : " (wrong windings alone are not retried)") +
           "; see the report's parameterization.wrong_winding_vertices and flipped_faces";
  // An attempt with another field or optimization than the first's is named by them (the fallbacks of
  // pipeline/retry_until_valid.h).
  const auto name = [&](const ValidityAttempt& a) {
    std::string differs;  // what it ran with other than the first attempt
    if (a.field_style != attempts[0].field_style) differs = "the " + to_string(a.field_style) + " field";
    if (a.optimize != attempts[0].optimize)
      differs += (differs.empty() ? "the " : " and the ") + std::string(to_string(a.optimize)) + " optimization";
    if (a.crisp_creases != attempts[0].crisp_creases)
      differs += (differs.empty() ? "" : " and ") +
                 std::string(a.crisp_creases ? "the short crisp creases" : "the long crease chains alone as features");
    const std::string at = "at " + percent(a.quads_factor) + " quads";
    if (differs.empty()) return at;
    return a.quads_factor == 1 ? "using " + differs : "using " + differs + " " + at;
  };
  std::string tried;
  for (std::size_t k = 1; k < attempts.size(); ++k) tried += (k > 1 ? ", " : "") + name(attempts[k]);
  const std::string first = "the result at the requested density was not valid (" + describe(attempts[0].validity) +
                            "); retried " + tried + " and kept ";
  const std::string which = kept.validity.valid() ? "a valid result" : "the best, with " + describe(kept.validity);
  return first + which + ", " + name(kept) + " (see the report's validity_retries)";
}

}  // namespace quadcover
