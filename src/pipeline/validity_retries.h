#pragma once
// Validity retries (issue 14, beyond the thesis): a map whose untangling and fold refinement leave a non-positive
// triangle or a ring wound other than the field says, or a quad mesh whose topology differs from the input's, is
// not a valid result. Which lattice the rounding meets depends on the density, and the untangler's failures are
// local: the same field at a slightly different density often gives a valid map. While the result has a
// non-positive triangle or a changed topology (worth_retrying), the job runs again at the next density of the
// sequence 1, 1.04, 0.96, 1.08, 0.92, … times the first attempt's quad count (1, 1.02, 0.98, 1.04, … when the
// user gave a quad count or an edge length: the default single retry stays within ±3 % of the request), at most
// PipelineOptions::validity_retries times, and keeps the first valid attempt or else the best (Validity order).
// Wrong windings alone do not start a retry: on the shipped meshes other densities rarely remove them and each
// retry costs a whole job (BENCHMARKS.md, "Validity retries"). Retries are improvements: a time limit or Ctrl-C
// stops them (ProgressSink::skip_improvements).
#include <string>
#include <tuple>
#include <vector>

#include "mesh/mesh.h"
#include "param/parameterization.h"
#include "pipeline/pipeline_options.h"

namespace quadcover {

/// How far a result is from valid; compared lexicographically in this order, lower is better.
struct Validity {
  int topology_changes = 0;  ///< remesh: components, genus or boundary loops of the quad mesh ≠ the input's
  int non_positive = 0;      ///< triangles of the map with UV area ≤ 0 (param/seams.h flipped_triangles)
  int wrong_windings = 0;    ///< interior vertices whose map winding ≠ the field's index (wrong_winding_vertices)
  int non_quads = 0;         ///< remesh: faces of the quad mesh that are not quads
  /// \pre none
  bool valid() const { return topology_changes == 0 && non_positive == 0 && wrong_windings == 0; }
  /// \pre none
  bool worth_retrying() const { return topology_changes > 0 || non_positive > 0; }
  /// \pre none
  bool operator<(const Validity& o) const {
    return std::tie(topology_changes, non_positive, wrong_windings, non_quads) <
           std::tie(o.topology_changes, o.non_positive, o.wrong_windings, o.non_quads);
  }
};

/// One attempt of the job: its density and how valid its result was.
struct ValidityAttempt {
  double quads_factor = 1;  ///< quad count asked for, relative to the first attempt's
  double edge_length = 0;   ///< h of its map (model units)
  Validity validity;
  FieldStyle field_style = FieldStyle::Curvature;  ///< the field stage's preset it ran with (resolved)
  double seconds = 0;  ///< wall time of its job: the attempts not kept cost time too, outside the kept job's stages
  OptimizeMode optimize = OptimizeMode::Relocate;  ///< Algorithm 6.1's mode it ran with
  /// Whether its field followed crisp short creases (FeatureOptions::crisp_crease_degrees > 0; off in the fallback
  /// to the long crease chains, pipeline/retry_until_valid.h).
  bool crisp_creases = true;
};

/// The interior vertices around which φ winds other than the field's cross-field index says (param/ring_winding.h
/// map_quarter_index against map.branch_points; 0 elsewhere): a fake cone pair, or a branch point whose ring folds.
/// Ascending. \pre map was made on mesh.
std::vector<int> wrong_winding_vertices(const Mesh& mesh, const Parameterization& map);

/// The quads the map holds: its signed parameter area (grid units²). \pre none
double map_quads(const Parameterization& map);

/// The map's part of Validity (non_positive, wrong_windings). \pre map was made on mesh.
Validity map_validity(const Mesh& mesh, const Parameterization& map);

/// The quad-count factor of attempt k (0-based): 1, 1.04, 0.96, 1.08, 0.92, … at the default density, in steps of
/// 2 % instead when `given` (the user's density) asks for a quad count or an edge length. \pre k >= 0
double attempt_quads_factor(int k, const DensityOptions& given);

/// The options `given` at the density of attempt k, with no retries inside: a requested quad count × factor, else
/// first_edge_length (attempt 0's h, the default density fixed) / √factor. \pre first_edge_length > 0, k >= 0.
PipelineOptions attempt_options(const PipelineOptions& given, double first_edge_length, int k);

/// The warning when the kept attempt is not the first or is not valid, naming what each attempt left.
/// \pre attempts non-empty, used < attempts.size().
std::string validity_warning(const std::vector<ValidityAttempt>& attempts, int used);

}  // namespace quadcover
