#pragma once
// The one report of a job: the CLI's --report JSON, the Python module's report dict and the data of the HTML page
// are this document (schema below, versioned). Every number about the map is measured on the coordinates as
// written, every number about the quad mesh on the mesh as written: what an independent checker of the files finds.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "common/stage_meter.h"
#include "mesh/mesh.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/remesh_mesh.h"

namespace quadcover {

/// Bumped whenever a key changes meaning or moves.
inline constexpr int kReportSchemaVersion = 1;

/// The report of the parameterization job. `uv` is the map as written (#F by 3 per-corner coordinates); `input`
/// names the source ("" from Python). Keys:
///   schema_version, job ("param"), input, mesh {vertices, faces, genus, boundary_loops, components}, options,
///   edge_length, density {target_quads, first_quads, quads, resolves, raised_for_loop, raised_quads_factor},
///   field {branch_points_initial, singularity_moves, cancelled_close_pairs {original, optimized},
///          branch_points [{vertex, quarter_index, index}], b_odd, b_even, unfixed_even_branch_points, features
///          {sharp_angle_degrees, boundaries, sharp_edges, constrained_faces}},
///   parameterization (metrics/report.h to_json(ParamQuality): flipped, collapsed and non-positive triangles, ARAP,
///          cones, seams; plus seamless, parameter_extent, cut_edges, parameter_area, flipped_faces, h_sym),
///   optimize, rounding, relaxation, stiffening, untangling, aligned_curves {curves, max_deviation, conflicts},
///   extraction, quad_mesh, surface_distance, feature_fidelity, quad_smoothing, surface_check, boundary_loops (null
///   for param),
///   warnings (sentences), seconds {stage: wall-clock seconds},
///   memory {peak_bytes (the process's peak resident bytes so far), input_faces (the input's triangles),
///           huge_pages (malloc asks for transparent huge pages, common/memory.h malloc_asks_for_huge_pages),
///           stages [{stage, peak_bytes, bytes_per_face}]}: per stage, in pipeline order, under the names of
///           `seconds`, the peak resident bytes of the whole process during it (Linux VmHWM, reset at each stage;
///           0 elsewhere; jobs run in parallel in one process include each other's memory), and that per input face.
///   seconds and memory are the only values that differ between two runs.
/// \pre uv is #F by 3.
nlohmann::json param_report(const Mesh& mesh, const ParamJob& job, const Eigen::MatrixX3cd& uv,
                            const std::string& input = "");

/// The report of the remesh job: param_report() of its map (job "remesh") plus extraction, quad_mesh (measured on
/// the smoothed quad mesh), surface_distance (to the input), feature_fidelity (metrics/feature_fidelity.h: the
/// input's boundary and sharp edges against the quad edges, in units of h), quad_smoothing and surface_check
/// (pipeline/surface_check.h: the quad mesh's components, boundary loops, χ, manifoldness against the input's) and
/// boundary_loops (pipeline/boundary_loop_check.h: per input loop {loop, first_vertex, edges, length, lines,
/// enforced_lines, non_quads, reason}); the metrics' seconds are added. \pre job = remesh(mesh, …).
nlohmann::json remesh_report(const Mesh& mesh, const RemeshJob& job, const std::string& input = "");

/// Adds a stage measured after the report was made (e.g. the CLI's writing of the outputs) to its seconds and memory
/// (common/stage_meter.h), and updates the process peak. \pre none
void add_report_stage(nlohmann::json& report, const std::string& stage, const StageCost& cost);

/// The key numbers of a report, flat (printed by the CLI, tabulated in batches): edge_length, branch_points (of the
/// map), h_sym, flipped_triangles, seamless, E_D, E_H, arap, optimize (without its log), rounding; for param the
/// input's vertices, faces, genus, boundary_loops; for remesh the quad mesh's vertices, faces, quads, non_quads,
/// rsd_edge_length, rsd_corner_angle, irregular_vertices, manifold, closed, and input_faces, same_topology,
/// features_covered_percent, distance_max, repairs. \pre none (absent keys are left out).
nlohmann::json report_summary(const nlohmann::json& report);

}  // namespace quadcover
