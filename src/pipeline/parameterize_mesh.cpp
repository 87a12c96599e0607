#include "pipeline/parameterize_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>

#include "common/side_by_side.h"
#include "field/compute_frame_field.h"
#include "field/crease_loops.h"
#include "field/feature_alignment.h"
#include "field/indices.h"
#include "mesh/vertex_rings.h"
#include "optimize/curl_energy.h"
#include "optimize/optimize_field.h"
#include "param/density.h"
#include "param/face_count.h"
#include "param/seams.h"
#include "pipeline/cone_merging.h"
#include "pipeline/cone_refinement.h"
#include "pipeline/memory_budget.h"
#include "pipeline/retry_until_valid.h"

namespace quadcover {

namespace {

/// Ends the stage `meter` measured under `stage` in the job's seconds and peak bytes.
void lap(StageMeter& meter, ParamJob& job, const char* stage) { meter.lap(stage, job.seconds, job.peak_bytes); }

/// Cancels in `field` the opposite branch point pairs closer than the quad edge (h, or h / ρ on a component of
/// density factor ρ: close_opposite_cone_merges) and smooths it again for the new matching. \return the pairs
/// cancelled.
int cancel_close_opposite_cones(const Mesh& mesh, const FrameFieldResult& stage, double lambda,
                                const DensityOptions& density, int field_branch_points, FrameField& field) {
  const double h = target_edge_length(mesh, density, field_branch_points);
  const std::vector<ConeMerge> pairs =
      close_opposite_cone_merges(mesh, branch_points(mesh, field), h, density.component_density);
  if (!pairs.empty()) field = merge_cones(mesh, stage, field, lambda, pairs);
  return static_cast<int>(pairs.size());
}

/// `both`: the cost of parameterize_keep_better. Where it also solved the original field, the time beyond the kept
/// map's own steps (its param_* entries) is the comparison's: recorded as "keep_better".
void record_comparison_solve(const StageCost& both, ParamJob& job) {
  if (!job.optimize.contains("E_D_plus_E_H_original")) return;
  double kept = 0;
  for (const auto& [stage, s] : job.map.diagnostics.stage_seconds) kept += s;
  job.seconds.emplace_back("keep_better", std::max(0.0, both.seconds - kept));
  job.peak_bytes.emplace_back("keep_better", both.peak_bytes);
}

/// The loops whose turning side the field leaves free below `max_length` (field/crease_loops.h free_side), as holes
/// for the default density.
std::vector<HoleRim> hole_rims(const std::vector<CreaseLoop>& loops, double max_length) {
  std::vector<HoleRim> rims;
  for (const CreaseLoop& loop : loops)
    if (free_side(loop, max_length) != 0)
      rims.push_back({*std::min_element(loop.vertices.begin(), loop.vertices.end()), loop.length});
  return rims;
}

/// The default density made finer for a boundary loop (param/density.h LoopResolution; r.loop ≥ 0), the loop
/// numbered as the report's boundary_loops number it (pipeline/boundary_loop_check.h), or for a hole rim (numbered
/// from 1 in DensityOptions::hole_rims).
LoopDensityRaise loop_density_raise(const Mesh& mesh, const LoopResolution& r, const DensityOptions& density) {
  LoopDensityRaise raise;
  raise.rim = r.rim;
  if (r.rim) {
    raise.loop = r.loop + 1;
  } else {
    raise.loop = 1;
    for (const auto& loop : mesh.boundary_loops())
      raise.loop += *std::min_element(loop.begin(), loop.end()) < r.lowest_vertex;
  }
  raise.vertex = r.lowest_vertex + 1;
  raise.at = mesh.V().row(r.lowest_vertex);
  raise.length = r.length;
  raise.quads_factor = r.quads_factor;
  raise.grid_units = density.min_loop_grid_units;
  return raise;
}

/// Fixes the default density of job.options (param/density.h fix_default_density): one scale for the optimization,
/// keep-better and the map. Made finer for a short boundary loop (job.density.raised) only when the memory holds
/// it; else the job says that it was not.
void fix_default_and_loop_density(const Mesh& mesh, const FrameField& field, std::int64_t available, ParamJob& job) {
  DensityOptions& density = job.options.param.density;
  const LoopResolution r = fix_default_density(mesh, field, density);
  if (r.loop < 0) return;
  const LoopDensityRaise raise = loop_density_raise(mesh, r, density);
  const double quads = requested_quads(mesh, job.options.param);
  if (fits_memory_budget(mesh, quads, available)) {
    job.density.raised = raise;
    return;
  }
  density.edge_length = r.edge_length;  // the coarser default
  char text[200];
  std::snprintf(text, sizeof text,
                "the default density was not made finer for %s %d (through vertex %d): about %.3g quads would not fit "
                "in the memory available",
                raise.rim ? "hole rim" : "boundary loop", raise.loop, raise.vertex, quads);
  job.warnings.push_back(text);
}

/// fix_default_and_loop_density, then, unless the user gave the edge length, a finer density on the components that
/// would have few quads for their branch points (param/density.h fix_component_density).
void fix_density(const Mesh& mesh, const FrameField& field, std::int64_t available, ParamJob& job) {
  DensityOptions& density = job.options.param.density;
  const bool length_given = density.edge_length > 0 && !density.edge_length_from_default;
  fix_default_and_loop_density(mesh, field, available, job);
  if (!length_given)
    fix_component_density(mesh, field, target_edge_length(mesh, density, job.field_branch_points), density);
}

/// The one-line summary of Algorithm 6.1 for the progress sink.
std::string optimize_summary(const nlohmann::json& r, double evaluations_per_second, long budget) {
  const std::string by = r["stopped_by"].get<std::string>();
  const std::string how = by == "converged"     ? "converged"
                          : by == "evaluations" ? "stopped on the budget of " + std::to_string(budget)
                                                : "stopped early (" + by + ")";
  char line[200];
  std::snprintf(line, sizeof line, "E_D %.4g -> %.4g, branch points %d -> %d, %ld evaluations (%.0f/s), %s",
                r["E_D_before"].get<double>(), r["E_D_after"].get<double>(), r["branch_points_before"].get<int>(),
                r["branch_points_after"].get<int>(), r["evaluations"].get<long>(), evaluations_per_second, how.c_str());
  return line;
}

/// With a time limit (progress.seconds_left() finite), Algorithm 6.1, the only stage that can stop with a usable
/// result at any moment, stops early enough to leave the stages after it their time, estimated from the field stage
/// (they take about kLaterStagesPerFieldSecond times as long on the shipped meshes, BENCHMARKS.md).
/// Returns true if the limit set is the caller's (tighter than the stage's own).
bool leave_time_for_later_stages(const Mesh& mesh, double field_seconds, double seconds_left, OptimizeOptions& oo) {
  if (!std::isfinite(seconds_left) || oo.mode == OptimizeMode::None) return false;
  constexpr double kLaterStagesPerFieldSecond = 10;
  const double budget = std::max(0.01, seconds_left - kLaterStagesPerFieldSecond * field_seconds);
  const double own = oo.time_limit_seconds > 0           ? oo.time_limit_seconds
                     : oo.max_evaluations == kAutoBudget ? auto_time_limit(mesh, oo.mode)
                                                         : 0.0;
  oo.time_limit_seconds = own > 0 ? std::min(own, budget) : budget;
  return own <= 0 || budget < own;
}

/// Records `stage` in job.cut_short when a stop (Ctrl-C, time limit: progress.skip_improvements()) had come by its end while
/// it still had work to do (`unfinished`).
void note_cut_short(const ProgressSink& progress, bool unfinished, ParamJob& job, const char* stage) {
  if (unfinished && progress.skip_improvements()) record_cut_short(job, stage);
}

/// The vertices within `rings` rings of the map's wrongly wound vertices, ascending.
std::vector<int> wrong_winding_spots(const Mesh& mesh, const Parameterization& map, int rings) {
  std::vector<char> flags(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const int v : wrong_winding_vertices(mesh, map)) flags[v] = 1;
  flags = grow_vertex_rings(mesh, std::move(flags), rings);
  std::vector<int> spots;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (flags[v]) spots.push_back(v);
  return spots;
}

/// Rounding the curves with the periods (param/curve_rounding.h) pins lines that a coarse triangulation cannot always
/// hold without a wrong winding (a cone beside a line's image, a fan too coarse for the lines through it; the fold
/// refinement later removes non-positive triangles, rarely wrong windings). While the job's map has wrong windings,
/// the lines through them (within kRings rings) are freed and the map made again with the others pinned, kept when
/// more valid (at most kRounds times). When some are left, the map with the period-matrix rounding alone is made as
/// well and goes on if more valid; the job's options then say which.
/// Their times are the stages "curve_freeing" and "curve_rounding_fallback".
void free_curves_at_wrong_windings(const Mesh& mesh, const FrameField& kept_field, ProgressSink& progress,
                                   ParamJob& job) {
  constexpr int kRounds = 2, kRings = 2;
  ParamOptions& param = job.options.param;
  const auto rounded = [&] { return job.map.diagnostics.rounding.curve_lines > 0; };
  if (!rounded()) return;
  Validity now = map_validity(mesh, job.map);  // of job.map
  if (now.wrong_windings == 0) return;
  StageMeter meter;
  for (int round = 0; round < kRounds && rounded() && now.wrong_windings > 0; ++round) {
    ParamOptions freeing = param;
    std::vector<int>& freed = freeing.alignment.free_line_vertices;
    const std::vector<int> spots = wrong_winding_spots(mesh, job.map, kRings);
    std::vector<int> all;
    std::set_union(freed.begin(), freed.end(), spots.begin(), spots.end(), std::back_inserter(all));
    freed = std::move(all);
    Parameterization map = parameterize(mesh, kept_field, freeing, progress);
    const Validity next = map_validity(mesh, map);
    if (!(next < now)) break;
    job.map = std::move(map);
    param = std::move(freeing);
    now = next;
  }
  lap(meter, job, "curve_freeing");
  if (!rounded() || now.wrong_windings == 0) return;
  ParamOptions plain = param;
  plain.alignment.round_with_periods = false;
  plain.alignment.free_line_vertices.clear();
  Parameterization map = parameterize(mesh, kept_field, plain, progress);
  lap(meter, job, "curve_rounding_fallback");
  if (!(map_validity(mesh, map) < now)) return;
  job.map = std::move(map);
  param = plain;
}

/// Rounds of cone moves (pipeline/cone_merging.h): `find` gives the moves on the job's map, the field with them
/// applied is smoothed and the map solved again, kept while `better(new map, old map)`; at most 3 rounds. Adds the
/// kept moves to `moved` and the rounds run to `rounds`.
template <class Find, class Better>
void cone_move_rounds(const Mesh& mesh, const FrameFieldResult& stage, double lambda, ParamJob& job,
                      ProgressSink& progress, const char* name, Find find, Better better, int& moved, int& rounds) {
  constexpr int kRounds = 3;
  for (int round = 0; round < kRounds; ++round) {
    const std::vector<ConeMerge> moves = find(mesh, job.map);
    if (moves.empty()) break;
    if (progress.skip_improvements()) {
      record_cut_short(job, name);
      break;
    }
    FrameField field = merge_cones(mesh, stage, job.field, lambda, moves);
    Parameterization map = parameterize(mesh, field, job.options.param, progress);
    ++rounds;
    if (!better(map, job.map)) break;
    job.field = std::move(field);
    job.map = std::move(map);
    moved += static_cast<int>(moves.size());
  }
}

/// Merges the branch point pairs the map puts on one point (coincident_cone_merges) while that leaves fewer
/// non-positive triangles, then moves the branch points of fake cone pairs to the vertex the map winds around
/// (wound_cone_moves) while the map gets more valid (fewer non-positive triangles, then fewer wrong windings).
void move_cones(const Mesh& mesh, const FrameFieldResult& stage, double lambda, ParamJob& job, ProgressSink& progress) {
  if (job.options.merge_coincident_cones)
    cone_move_rounds(
        mesh, stage, lambda, job, progress, "cone merging", coincident_cone_merges,
        [](const Parameterization& next, const Parameterization& now) {
          return next.diagnostics.untangling.non_positive_after < now.diagnostics.untangling.non_positive_after;
        },
        job.merged_cone_pairs, job.merge_rounds);
  if (job.options.move_wound_cones)
    cone_move_rounds(
        mesh, stage, lambda, job, progress, "wound cone moves", wound_cone_moves,
        [&](const Parameterization& next, const Parameterization& now) {
          return map_validity(mesh, next) < map_validity(mesh, now);
        },
        job.moved_wound_cones, job.wound_cone_rounds);
}

/// The fold refinement stage (pipeline/fold_refinement.h) on the map's mesh; a kept result replaces the job's mesh,
/// field and map, its splits appended to job.refinement. `mesh` (job.mesh(input)) may be gone afterwards.
void refine_job_folds(const Mesh& mesh, ParamJob& job, ProgressSink& progress) {
  const FoldRefinementOptions options{job.options.fold_refinement_rounds, job.options.param.untangle};
  FoldRefinement r = refine_folds(mesh, job.field, job.map, options, progress);
  job.fold_refinement = r.report;
  if (!r.mesh) return;
  job.refinement.mesh = std::move(r.mesh);
  job.refinement.split.insert(job.refinement.split.end(), r.split.begin(), r.split.end());
  job.refinement.added_faces += r.report.added_faces;
  job.field = std::move(r.field);
  job.map = std::move(r.map);
}

/// The sentences for a refined triangulation (the first `before_folds` of job.refinement.split by the curve and the
/// cone refinement, the rest by the fold refinement) and for triangles left non-positive.
std::vector<std::string> refinement_warnings(const ParamJob& job, std::size_t before_folds) {
  std::vector<std::string> w;
  const std::size_t splits = job.refinement.split.size(), fold_splits = splits - before_folds;
  const std::size_t cone_splits = static_cast<std::size_t>(job.cone_splits), curve_splits = before_folds - cone_splits;
  if (job.refinement.mesh) {
    std::string why;
    if (curve_splits > 0)
      why = std::to_string(curve_splits) + " where a triangle had its three corners on boundary or feature curves";
    if (cone_splits > 0)
      why += (why.empty() ? "" : ", ") + std::to_string(cone_splits) +
             " at field singularities of index 3/4 or more with too few interior vertices around to split them "
             "into quarter cones";
    if (fold_splits > 0)
      why += (why.empty() ? "" : ", ") + std::to_string(fold_splits) +
             " around triangles the untangling could not make positive on the coarser triangulation";
    w.push_back("the map is on a refined triangulation: " + std::to_string(splits) + " edges split at their midpoints (" +
                why + "; " + std::to_string(job.refinement.added_faces) +
                " triangles added; the input's vertices keep their numbers, see the report's refinement)");
  }
  const ParamDiagnostics::Untangling& u = job.map.diagnostics.untangling;
  if (u.non_positive_after > 0)
    w.push_back(std::to_string(u.non_positive_after) + " triangles of the map stay flipped or collapsed (" +
                std::to_string(u.stuck_faces.size()) + " held at zero area by the seams, cones and curve constraints, " +
                std::to_string(u.unresolved_faces.size()) + " the untangling could not unfold" +
                (job.fold_refinement.rounds > 0
                     ? ", after " + std::to_string(job.fold_refinement.rounds) + " rounds of fold refinement"
                     : std::string()) +
                "); the quad mesh may fold there (see the report's untangling and fold_refinement)");
  return w;
}

}  // namespace

std::string loop_density_warning(const LoopDensityRaise& raise) {
  char text[400];
  std::snprintf(text, sizeof text,
                "the default density was made %.1f times finer (quads) so that %s %d (through vertex %d at "
                "(%.6g, %.6g, %.6g), length %.6g) is %g quad edges around and keeps a ring of quads (pass --faces or "
                "--edge-length to choose)",
                raise.quads_factor, raise.rim ? "the rim of hole" : "boundary loop", raise.loop, raise.vertex,
                raise.at.x(), raise.at.y(), raise.at.z(), raise.length, raise.grid_units);
  return text;
}

DensityReport hit_target_count(const Mesh& mesh, ParamJob& job, ProgressSink& progress, int target_quads) {
  ParamOptions& param = job.options.param;
  DensityReport d;
  d.raised = job.density.raised;  // how the default density was fixed stays
  d.target_quads = target_quads;
  d.quads = d.first_quads = expected_face_count(mesh, job.map.uv);
  if (target_quads <= 0 || d.first_quads <= 0) return d;
  const double target = target_quads;
  StageMeter meter;
  // Quad count ≈ c / h²: re-solve the kept field (field and matching stay) at the h this predicts, interpolating in
  // log h between the closest tries below and above N once both exist (the periods round to the lattice, so the
  // count moves in steps); the closest map is kept.
  std::pair<double, double> below{0, 0}, above{0, 0};  // (h, count) with count < N, count > N
  auto note = [&](double h, double count) { (count < target ? below : above) = {h, count}; };
  note(job.map.edge_length, d.quads);
  double h = job.map.edge_length, count = d.quads;
  for (int k = 0; k < kDensityResolves && std::abs(d.quads / target - 1) > kDensityTolerance; ++k) {
    if (below.first > 0 && above.first > 0) {  // count falls with h: above has the smaller h
      const double s = std::log(target / above.second) / std::log(below.second / above.second);
      h = above.first * std::pow(below.first / above.first, s);
    } else {
      h *= std::sqrt(count / target);
    }
    param.density.edge_length = h;
    param.density.target_quads = 0;
    Parameterization map = parameterize(mesh, job.field, param, progress);
    count = expected_face_count(mesh, map.uv);
    note(h, count);
    ++d.resolves;
    if (std::abs(count / target - 1) < std::abs(d.quads / target - 1)) {
      job.map = std::move(map);
      d.quads = count;
    }
    if (progress.skip_improvements()) break;
  }
  param.density.edge_length = job.map.edge_length;
  note_cut_short(progress, std::abs(d.quads / target - 1) > kDensityTolerance && d.resolves < kDensityResolves, job,
                 "density re-solves");
  if (d.resolves > 0) lap(meter, job, "density");
  return d;
}

namespace {

/// The one warning for the improving stages a stop skipped or cut short, in the words the CLI prints.
std::string cut_short_warning(const std::vector<std::string>& stages) {
  std::string list;
  for (const std::string& s : stages) list += (list.empty() ? "" : ", ") + s;
  return "stopped (Ctrl-C or time limit) before the job finished: skipped or cut short: " + list +
         "; the result is complete and checked, a run without the limit would improve it";
}

}  // namespace

void record_cut_short(ParamJob& job, std::string stage) {
  const auto said = job.cut_short.empty()
                        ? job.warnings.end()
                        : std::find(job.warnings.begin(), job.warnings.end(), cut_short_warning(job.cut_short));
  job.cut_short.push_back(std::move(stage));
  if (said == job.warnings.end())
    job.warnings.push_back(cut_short_warning(job.cut_short));
  else
    *said = cut_short_warning(job.cut_short);
}

std::vector<std::string> map_warnings(const Parameterization& map) {
  std::vector<std::string> warnings;
  for (int comp : map.diagnostics.holonomy_without_branch_points)
    warnings.push_back("component " + std::to_string(comp) +
                       ": the field turns around a handle but has no branch points; no seamless immersion exists "
                       "there (the map degenerates). Use a field with branch points (e.g. --optimize full).");
  if (!map.diagnostics.unfixed_even_branch_points.empty())
    warnings.push_back(std::to_string(map.diagnostics.unfixed_even_branch_points.size()) +
                       " even branch points stay on half-integers (see unfixed_even_branch_points)");
  return warnings;
}

/// Cones rounded onto one lattice point a few edges apart (close_coincident_merges) fold the map beside them in a way
/// that no untangling or refinement undoes. When the job's final map is not valid, it is made again from `before`
/// (the job before the cone moves, without its map) with those pairs merged: the pairs `early` found on the first
/// map and those on the final one. Then the kinds of cone moves the first pass kept, density and fold refinement;
/// kept when more valid, and once more with the pairs on the new final map while it is not valid.
/// Its time is the stage "close_cone_merging".
/// `before` made again with `merges` applied to its field: map, the cone moves in `moves` (merge, move), density
/// and fold refinement. With a requested quad count the map starts at `found_edge_length`, the h the job's density
/// stage settled on, so that the density stage re-solves only when the merges moved the count.
ParamJob remade_with_merges(const Mesh& mesh, const FrameFieldResult& stage, double lambda, const ParamJob& before,
                            const std::vector<ConeMerge>& merges, std::pair<bool, bool> moves, double found_edge_length,
                            ProgressSink& progress) {
  ParamJob retry = before;
  DensityOptions& density = retry.options.param.density;
  const int target_quads = density.target_quads;
  if (target_quads > 0 && found_edge_length > 0) density.edge_length = found_edge_length, density.target_quads = 0;
  retry.field = merge_cones(mesh, stage, retry.field, lambda, merges);
  retry.map = parameterize(mesh, retry.field, retry.options.param, progress);
  retry.merged_cone_pairs += static_cast<int>(merges.size());
  ++retry.merge_rounds;
  PipelineOptions& o = retry.options;
  const bool merge = o.merge_coincident_cones, move = o.move_wound_cones;
  o.merge_coincident_cones = merge && moves.first;
  o.move_wound_cones = move && moves.second;
  move_cones(mesh, stage, lambda, retry, progress);
  o.merge_coincident_cones = merge;
  o.move_wound_cones = move;
  retry.density = hit_target_count(mesh, retry, progress, target_quads);
  refine_job_folds(mesh, retry, progress);
  return retry;
}

namespace {

/// Appends to `merges` the pairs of close_coincident_merges(map, reach, AlsoFolds) whose vertices `used` leaves free
/// (and are vertices of `mesh`: no midpoint of the fold refinement is a cone), marking them used. \return how many.
std::size_t add_close_merges(const Mesh& mesh, const Mesh& map_mesh, const Parameterization& map, CoincidentReach reach,
                             std::vector<char>& used, std::vector<ConeMerge>& merges) {
  const std::size_t known = merges.size();
  for (const ConeMerge& m : close_coincident_merges(map_mesh, map, reach, CoincidentCause::AlsoFolds))
    if (m.from < mesh.num_vertices() && m.into < mesh.num_vertices() && !used[m.from] && !used[m.into]) {
      merges.push_back(m);
      used[m.from] = used[m.into] = 1;
    }
  return merges.size() - known;
}

}  // namespace

void merge_close_cones(const Mesh& input, const FrameFieldResult& stage, double lambda, const ParamJob& before,
                       std::vector<ConeMerge> merges, ParamJob& job, ProgressSink& progress) {
  // Rounds while not valid: the remade map can put another pair on a point. The far partners are looked for once
  // the near ones are spent (none new, or their remake was not kept).
  constexpr int kRounds = 3;
  if (!job.options.merge_coincident_cones) return;
  Validity now = map_validity(job.mesh(input), job.map);
  if (now.valid()) return;
  const Mesh& mesh = before.mesh(input);
  const std::pair<bool, bool> kept_moves{job.merged_cone_pairs > 0, job.moved_wound_cones > 0};
  std::vector<char> used(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const ConeMerge& m : merges) used[m.from] = used[m.into] = 1;
  StageMeter meter;
  bool far_tried = false, far_next = false, tried = false;
  for (int round = 0; round < kRounds; ++round) {
    const std::size_t known = merges.size();
    const auto add = [&](CoincidentReach reach) {
      return add_close_merges(mesh, job.mesh(input), job.map, reach, used, merges);
    };
    const std::size_t near = far_next ? 0 : add(CoincidentReach::Near);
    if (near == 0 && (round > 0 || known == 0)) {
      if (far_tried) break;
      far_tried = true;
      if (add(CoincidentReach::Far) == 0) break;
    }
    far_next = false;
    tried = true;
    ParamJob retry = remade_with_merges(mesh, stage, lambda, before, merges, kept_moves, job.map.edge_length, progress);
    const Validity remade = map_validity(retry.mesh(input), retry.map);
    if (!(remade < now)) {
      merges.resize(known);  // the pairs stay used: not tried again
      if (far_tried || progress.skip_improvements()) break;
      far_next = true;
      continue;
    }
    retry.seconds = std::move(job.seconds);
    retry.peak_bytes = std::move(job.peak_bytes);
    job = std::move(retry);
    now = remade;
    if (now.valid() || progress.skip_improvements()) break;
  }
  if (tried) lap(meter, job, "close_cone_merging");
}

/// The stages after the first map (job.map made from job.field): cone moves, density, fold refinement and the merges
/// of close cones; their times into job.seconds.
void settle_map(const Mesh& input, const FrameFieldResult& field, double lambda, ProgressSink& progress,
                ParamJob& job) {
  FinishingProgress finishing(progress);
  StageMeter meter;
  const Mesh& mesh = job.mesh(input);
  Parameterization first_map = std::move(job.map);
  ParamJob before_moves = job;  // without the map: merge_close_cones starts again from here
  job.map = std::move(first_map);
  std::vector<ConeMerge> close_merges;
  if (!map_validity(mesh, job.map).valid()) close_merges = close_coincident_merges(mesh, job.map);
  move_cones(mesh, field, lambda, job, finishing);
  if (job.merge_rounds + job.wound_cone_rounds > 0) lap(meter, job, "cone_merging");
  job.density = hit_target_count(mesh, job, finishing, job.options.param.density.target_quads);
  meter.restart();
  refine_job_folds(mesh, job, finishing);  // `mesh` may be gone from here on
  note_cut_short(progress, job.map.diagnostics.untangling.non_positive_after > 0, job, "fold refinement");
  if (job.fold_refinement.rounds > 0) lap(meter, job, "fold_refinement");
  merge_close_cones(input, field, lambda, before_moves, std::move(close_merges), job, finishing);
}

/// Whether a vertex the map winds wrong or a corner of a non-positive triangle lies within kWatchedRings + 1 rings of
/// a vertex of `pairs` (vertex numbers of `mesh` or of the mesh it refines). \pre map was made on mesh.
bool invalid_beside(const Mesh& mesh, const Parameterization& map, const std::vector<std::pair<int, int>>& pairs) {
  if (pairs.empty()) return false;
  std::vector<char> invalid(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const int v : wrong_winding_vertices(mesh, map)) invalid[v] = 1;
  for (const int f : flipped_triangles(mesh, map.uv).flipped_faces)
    for (int c = 0; c < 3; ++c) invalid[mesh.F()(f, c)] = 1;
  const std::vector<char> near = grow_vertex_rings(mesh, std::move(invalid), kWatchedRings + 1);
  return std::any_of(pairs.begin(), pairs.end(), [&](const auto& pair) {
    return (pair.first < mesh.num_vertices() && near[pair.first]) ||
           (pair.second < mesh.num_vertices() && near[pair.second]);
  });
}

/// When the settled map is not valid beside branch points that the first map's rounding put on one point
/// (invalid_beside): `first` (the job at its first map) made again with those cones set apart
/// (ParamOptions::separate_close_cones) and settled; kept when more valid. Its time is the stage
/// "cone_separation" (its own stages are not listed).
void settle_with_separated_cones(const Mesh& input, const FrameFieldResult& field, double lambda,
                                 ProgressSink& progress, ParamJob first, ParamJob& job) {
  if (progress.skip_improvements()) return record_cut_short(job, "cone separation");
  StageMeter meter;
  FinishingProgress finishing(progress);
  first.options.param.separate_close_cones = true;
  first.map = parameterize(first.mesh(input), first.field, first.options.param, finishing);
  settle_map(input, field, lambda, progress, first);
  const Validity separated = map_validity(first.mesh(input), first.map);
  const bool kept = separated < map_validity(job.mesh(input), job.map);
  if (kept) {
    first.seconds = std::move(job.seconds);  // the stages of the separated job are its own entry
    first.peak_bytes = std::move(job.peak_bytes);
    job = std::move(first);
  }
  job.cone_separation = {true, kept, separated};
  lap(meter, job, "cone_separation");
}

/// The field stage, and beside it when the optimization runs (common/side_by_side.h: below 100k faces) the ordering
/// of the optimization's factor, which depends on the mesh only (optimize/curl_energy.h order_curl_energy_ahead).
FrameFieldResult field_and_ordering(const Mesh& mesh, const PipelineOptions& options, ProgressSink& progress) {
  if (options.optimize == OptimizeMode::None)
    return compute_frame_field_detailed(mesh, field_stage_options(options), progress);
  std::optional<FrameFieldResult> field;
  run_side_by_side(
      mesh.num_faces(), [&] { field = compute_frame_field_detailed(mesh, field_stage_options(options), progress); },
      [&] { order_curl_energy_ahead(mesh); });
  return std::move(*field);
}

/// The field stage on the job's mesh. While the field keeps a singularity of three quarters or more that its split
/// could not spread over interior vertices nearby (pipeline/cone_refinement.h), the edges at it are split and the
/// field is made again on the refined mesh, at most kConeRefinementRounds times. A half cone left as it is can be
/// mapped (a quad vertex of valence 2 or 6: the corners of a tetrahedron); a 3/4 cone is a valence-1 spike and a
/// whole turn a cone of angle 0 (the map folds flat) or 4π.
FrameFieldResult field_on_refined_mesh(const Mesh& input, ParamJob& job, ProgressSink& progress) {
  constexpr int kConeRefinementRounds = 2;
  FrameFieldResult field = field_and_ordering(job.mesh(input), job.options, progress);
  const FieldOptions options = field_stage_options(job.options);
  if (!options.split_singularities) return field;
  const int min_quarters = std::max(3, options.split_min_quarters);
  for (int round = 0; round < kConeRefinementRounds; ++round) {
    const std::vector<int> stuck = unsplit_singularities(job.mesh(input), field.field, min_quarters);
    if (stuck.empty()) break;
    const std::size_t before = job.refinement.split.size();
    refine_around_vertices(job.mesh(input), stuck, job.refinement);
    job.cone_splits += static_cast<int>(job.refinement.split.size() - before);
    field = field_and_ordering(job.mesh(input), job.options, progress);
  }
  return field;
}

/// field_on_refined_mesh with the short crease loops freed on their turning side (FeatureOptions::
/// free_short_loops_below: PipelineOptions::square_hole_grid_units quad edges h). h is first taken from the mesh
/// alone (target_edge_length without branch points, at least the default h); when the field's branch points make
/// the default h finer and so fewer loops that short, the field is made again with those. The loops are traced from
/// `sharp_edges`, the input's sharp edges the field follows (followed_sharp_edges); the freed ones are the density's
/// hole rims (param/density.h).
FrameFieldResult field_with_square_holes(const Mesh& input, const std::vector<int>& sharp_edges, ParamJob& job,
                                         ProgressSink& progress) {
  ParamOptions& param = job.options.param;
  const double units = job.options.square_hole_grid_units;
  param.features.free_short_loops_below = units * target_edge_length(input, param.density);
  std::vector<CreaseLoop> loops;
  if (param.features.free_short_loops_below > 0) loops = closed_crease_loops(input, sharp_edges);
  param.density.hole_rims = hole_rims(loops, param.features.free_short_loops_below);
  FrameFieldResult field = field_on_refined_mesh(input, job, progress);
  if (param.density.hole_rims.empty()) return field;
  DensityOptions without_rims = param.density;
  without_rims.hole_rims.clear();
  const int branch_points = static_cast<int>(field.branch_points.size());
  param.features.free_short_loops_below = units * target_edge_length(input, without_rims, branch_points);
  const std::vector<HoleRim> rims = hole_rims(loops, param.features.free_short_loops_below);
  if (rims.size() == param.density.hole_rims.size()) return field;
  param.density.hole_rims = rims;
  return field_on_refined_mesh(input, job, progress);
}

ParamJob parameterize_once(const Mesh& input, const PipelineOptions& options, ProgressSink& progress,
                           const FirstMapCheck& check) {
  validate(options);
  check_memory_budget(input, options.param, available_bytes(options.max_memory_bytes));
  ParamJob job;
  job.options = options;
  job.options.field_style = resolved_field_style(options.field_style, input);
  job.field_style_auto = options.field_style == FieldStyle::Auto;
  ParamOptions& param = job.options.param;
  StageMeter meter;
  if (options.refine_curve_triangles && param.alignment.enabled) {
    job.refinement = refine_for_curves(input, param.features);
    if (job.refinement.mesh) lap(meter, job, "refinement");
  }
  // Crisp short creases shorter than the quad edge asked for crowd the field's cones; the default density is made fine
  // enough for the cones (30 quads a branch point, param/density.h), whatever they follow.
  const bool requested = param.density.target_quads > 0 || param.density.edge_length > 0;
  param.features.crisp_min_length = requested ? target_edge_length(input, param.density) : 0;
  const FollowedSharpEdges sharp = followed_sharp_edges(input, param.features);
  job.crisp_creases = sharp.crisp;
  const FrameFieldResult field = field_with_square_holes(input, sharp.edges, job, progress);
  const Mesh& mesh = job.mesh(input);
  job.field_branch_points = static_cast<int>(field.branch_points.size());
  job.field_singularity_moves = static_cast<int>(field.singularity_moves.size());
  lap(meter, job, "field");
  fix_density(mesh, field.field, available_bytes(options.max_memory_bytes), job);
  OptimizeOptions oo = optimize_stage_options(job.options, param);
  const bool limited = leave_time_for_later_stages(mesh, job.seconds.back().second, progress.seconds_left(), oo);
  const std::string mode = to_string(options.optimize);
  if (oo.mode != OptimizeMode::None) progress.report("optimize", 0, "Algorithm 6.1 (" + mode + ")");
  OptimizeResult optimized = optimize_field(mesh, field, oo, progress);
  job.optimize = to_json(optimized, oo.mode);
  job.optimize["rounding"] = to_string(param.rounding.strategy);
  if (oo.mode != OptimizeMode::None)
    progress.report("optimize", 1,
                    optimize_summary(job.optimize, optimized.evaluations_per_second, optimized.max_evaluations));
  lap(meter, job, "optimize");
  const std::string stopped_by = job.optimize.value("stopped_by", "converged");
  if (stopped_by == "cancelled" || (stopped_by == "time" && limited))
    job.warnings.push_back("the optimization was stopped early (" + stopped_by +
                           ") and kept its best field so far; the map was completed from it");
  // From here on every stage runs to the end: a stopped run still gives a valid, complete map.
  FinishingProgress finishing(progress);
  if (options.cancel_close_cones) {  // in the field the map is meant to be made from; keep-better's other one as it is
    job.cancelled_close_pairs =
        cancel_close_opposite_cones(mesh, field, oo.lambda, param.density, job.field_branch_points, optimized.field);
    lap(meter, job, "cone_cancelling");
  }
  job.map = parameterize_keep_better(mesh, field.field, optimized.field, param, oo.mode, options.keep_better, finishing,
                                     job.optimize);
  record_comparison_solve(meter.lap(), job);
  job.field = job.optimize.value("kept", "optimized") == "original" ? field.field : std::move(optimized.field);
  free_curves_at_wrong_windings(mesh, job.field, finishing, job);
  if (check) check(mesh, job.map);
  note_cut_short(progress, options.keep_better && oo.mode != OptimizeMode::None && !job.optimize.contains("E_D_plus_E_H_original"),
                 job, "keep-better");
  note_cut_short(progress, job.map.diagnostics.rounding.stopped_early, job, "rounding search");  // also ends on its own budget
  if (job.map.diagnostics.relaxation.stopped_early) record_cut_short(job, "relaxation");
  for (const auto& [stage, s] : job.map.diagnostics.stage_seconds) job.seconds.emplace_back("param_" + stage, s);
  for (const auto& [stage, b] : job.map.diagnostics.stage_peak_bytes) job.peak_bytes.emplace_back("param_" + stage, b);
  const std::size_t before_folds = job.refinement.split.size();
  std::optional<ParamJob> first;  // at the first map: settle_with_separated_cones starts again from here
  if (options.separate_coincident_cones && !param.separate_close_cones &&
      !job.map.diagnostics.rounding.coincident_cones.empty())
    first = job;
  settle_map(input, field, oo.lambda, progress, job);
  if (first && invalid_beside(job.mesh(input), job.map, first->map.diagnostics.rounding.coincident_cones))
    settle_with_separated_cones(input, field, oo.lambda, progress, std::move(*first), job);
  // The maps the stages after the fallback made do not know it: the options say it.
  job.map.diagnostics.rounding.curve_rounding_dropped =
      options.param.alignment.round_with_periods && !job.options.param.alignment.round_with_periods;
  for (std::string& w : map_warnings(job.map)) job.warnings.push_back(std::move(w));
  for (std::string& w : refinement_warnings(job, before_folds)) job.warnings.push_back(std::move(w));
  return job;
}

ParamJob parameterize_mesh(const Mesh& input, const PipelineOptions& options, ProgressSink& progress) {
  return retry_until_valid(
      options, [&](const PipelineOptions& o) { return parameterize_once(input, o, progress); },
      [&](const ParamJob& job) { return map_validity(job.mesh(input), job.map); }, progress);
}

}  // namespace quadcover
