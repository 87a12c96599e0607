#pragma once
// The metrics Report: one plain struct collecting every stage's numbers, serialized to JSON with fixed keys.
// The CLI (`metrics`, `remesh`), benchmarks and the HTML report all print this same Report.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "metrics/param_quality.h"
#include "metrics/quad_quality.h"
#include "metrics/surface_distance.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"

namespace quadcover {

struct Report {
  std::string input;                          ///< file the numbers are about
  std::optional<ParamQuality> parameterization;
  std::optional<ExtractionReport> extraction;
  std::optional<QuadQuality> quad_mesh;
  std::optional<SurfaceDistance> surface_distance;
  std::map<std::string, double> seconds;      ///< wall time per stage
  std::map<std::string, double> values;       ///< further named numbers (e.g. field energies, options used)
};

/// Keys (always present, null when absent): "input", "parameterization", "extraction", "quad_mesh",
/// "surface_distance", "seconds", "values". Nested keys are the struct member names. \pre none
nlohmann::json to_json(const Report& report);
nlohmann::json to_json(const ParamQuality& q);  ///< without the per-face array \pre none
nlohmann::json to_json(const QuadQuality& q);  ///< \pre none
nlohmann::json to_json(const SurfaceDistance& d);  ///< \pre none
nlohmann::json to_json(const ExtractionReport& r);  ///< \pre none
/// The period rounding of a map (6.3): the strategy asked for and the one used, E_H, h_sym, the number of real
/// variables, E_H predicted for direct and for the chosen rounding, candidates, proven_optimal, stopped_early.
/// \pre none
nlohmann::json rounding_to_json(const ParamOptions& options, const Parameterization& p);

/// The ARAP relaxation of a map (param/relaxation.h): rounds, ARAP distortion at the grid scale before and after,
/// and its price E_R. \pre none
nlohmann::json relaxation_to_json(const Parameterization& p);
/// The local stiffening of a map (param/stiffening.h): re-solves, the one kept, flipped triangles before and after,
/// and its price E_K (E_D + E_H + E_K = ½‖X̃ − ∇φ̃‖²). \pre none
nlohmann::json stiffening_to_json(const Parameterization& p);
/// The untangling of a map (param/untangle.h): Newton iterations of the barrier and of the polish, non-positive
/// triangles before and after, the faces the subspace holds at zero area (stuck) and the others left (unresolved),
/// the smallest det J, and its price E_U. Its seconds are under the report's "seconds". \pre none
nlohmann::json untangling_to_json(const Parameterization& p);
/// The tangential smoothing of a quad mesh (quad/smooth_quads.h): the options used and what it did. \pre none
nlohmann::json quad_smoothing_to_json(const QuadSmoothingOptions& options, const QuadSmoothingReport& r);

/// Human-readable lines ("RSD edge length: 8.1 %"), one per key number, for the CLI. \pre none
std::string to_text(const Report& report);

}  // namespace quadcover
