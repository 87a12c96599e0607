#include "field/compute_frame_field.h"

#include <tbb/parallel_invoke.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "common/errors.h"
#include "field/indices.h"
#include "field/matching.h"
#include "field/power_field.h"
#include "field/propagation.h"
#include "field/smoothing.h"

namespace quadcover {

FieldStyle parse_field_style(std::string_view name) {
  if (name == "curvature") return FieldStyle::Curvature;
  if (name == "smooth") return FieldStyle::Smooth;
  if (name == "auto") return FieldStyle::Auto;
  throw InputError("field", 0, "unknown field style '" + std::string(name) + "' (expected auto, curvature or smooth)");
}

std::string to_string(FieldStyle style) {
  switch (style) {
    case FieldStyle::Smooth:
      return "smooth";
    case FieldStyle::Auto:
      return "auto";
    default:
      return "curvature";
  }
}

FieldStyle resolved_field_style(FieldStyle style, const Mesh& mesh) {
  if (style != FieldStyle::Auto) return style;
  return mesh.num_boundary_loops() > 0 ? FieldStyle::Curvature : FieldStyle::Smooth;
}

Fill parse_fill(std::string_view name) {
  if (name == "propagate") return Fill::Propagate;
  if (name == "smooth") return Fill::Smooth;
  throw InputError("fill", 0, "unknown fill '" + std::string(name) + "' (expected propagate or smooth)");
}

std::string to_string(Fill fill) { return fill == Fill::Propagate ? "propagate" : "smooth"; }

FieldOptions field_options(FieldStyle style) {
  if (style == FieldStyle::Auto) throw std::logic_error("field_options: resolve FieldStyle::Auto first");
  FieldOptions o;
  if (style == FieldStyle::Smooth) {
    o.lambda = 1.0;
    o.fill_alignment = 0.1;
  }
  return o;
}

namespace {

// Power field aligned to the trusted frames with weight ω_t^stable (5.2), normalized to mean 1 over them, and held
// at the feature directions X on the constrained faces.
PowerFieldProblem power_fill_problem(const FrameFieldResult& r, const Eigen::VectorXcd& X,
                                     const FieldOptions& options) {
  const auto nf = static_cast<int>(X.size());
  PowerFieldProblem problem;
  problem.target = X;
  problem.weight = Eigen::VectorXd::Zero(nf);
  double sum = 0;
  int count = 0;
  for (int t = 0; t < nf; ++t)
    if (r.trusted[static_cast<std::size_t>(t)] && !r.constrained[static_cast<std::size_t>(t)]) {
      problem.weight[t] = r.stability[t];
      sum += r.stability[t];
      ++count;
    }
  if (sum > 0) problem.weight *= count / sum;
  problem.fixed = r.constrained;
  problem.alignment = options.fill_alignment;
  problem.unit_weight = options.fill_unit_weight;
  problem.iterations = options.fill_iterations;
  return problem;
}

// β per face: the rotation from X_t to the nearest curvature direction on trusted faces, 0 elsewhere.
Eigen::VectorXd curvature_targets(const FrameFieldResult& r, const Eigen::VectorXcd& X) {
  Eigen::VectorXd beta = Eigen::VectorXd::Zero(X.size());
  for (Eigen::Index t = 0; t < X.size(); ++t)
    if (r.trusted[static_cast<std::size_t>(t)]) beta[t] = 0.25 * std::arg(std::pow(r.curvature.direction[t] / X[t], 4));
  return beta;
}

// Straightest matching (5.1) of the smoothed frames α, expressed as changes of the smoother's matching
// (θ_e - α_s + α_t is the smoothed frames' curvature). Returns the number of edges changed.
int straighten_matching(const Mesh& mesh, FrameSmoother& smoother, const Eigen::VectorXd& alpha) {
  int changed = 0;
  const Eigen::VectorXd& theta = smoother.curvature();
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (mesh.is_boundary_edge(e)) continue;
    const double smoothed = theta[e] - alpha[mesh.EF()(e, 0)] + alpha[mesh.EF()(e, 1)];
    const int k = static_cast<int>(std::lround(2.0 * smoothed / std::numbers::pi));
    if (k != 0) {
      smoother.change_matching(e, k);
      ++changed;
    }
  }
  return changed;
}

// Smoothing (5.3) of r.field in rounds, re-choosing the straightest matching between rounds.
void smooth_field(const Mesh& mesh, const FieldOptions& options, FrameSmoother& smoother, FrameFieldResult& r,
                  ProgressSink& progress) {
  progress.report("field", 0.5, "smoothing (5.3)");
  smoother.set_input(r.field);
  // E_A measures the deviation from the original curvature directions on the trusted faces (5.3), which
  // the power fill does not reproduce exactly: β_t = the rotation from X_t to the nearest of the four
  // curvature directions. Propagated trusted frames are the curvature frames themselves (β = 0).
  if (options.fill == Fill::Smooth) smoother.set_alignment_targets(curvature_targets(r, r.field.X));
  Eigen::VectorXd alpha = smoother.solve();
  for (int round = 1; round < options.smoothing_rounds && !progress.cancelled(); ++round) {
    if (straighten_matching(mesh, smoother, alpha) == 0) break;
    alpha = smoother.solve();
  }
  r.field = smoother.rotated(alpha);
  r.energy_smooth = smoothing_energy(mesh, r.field);
  r.energy_align = smoother.alignment_energy(alpha);
}

// Quarter moves along paths (5.2.2) leave no |index| >= split_min_quarters; the frames are then smoothed (5.3) once
// more with that matching, starting from the current field (its θ is small, so ±π/2 changes never wrap).
void split_singularities(const Mesh& mesh, const FieldOptions& options, std::unique_ptr<FrameSmoother>& smoother,
                         FrameFieldResult& r) {
  r.singularity_moves =
      plan_singularity_split(mesh, cross_field_quarter_index(mesh, r.field), options.split_min_quarters);
  if (r.singularity_moves.empty()) return;
  FrameField split = r.field;
  apply_quarter_moves(mesh, r.singularity_moves, split.matching);
  if (!smoother)
    smoother = std::make_unique<FrameSmoother>(mesh, r.stability, r.trusted, r.constrained, options.lambda);
  smoother->set_alignment_targets(curvature_targets(r, split.X));  // E_A towards the curvature directions
  smoother->set_input(split);
  const Eigen::VectorXd alpha = smoother->solve();
  r.field = smoother->rotated(alpha);
  r.energy_smooth = smoothing_energy(mesh, r.field);
  r.energy_align = smoother->alignment_energy(alpha);
}

}  // namespace

FrameFieldResult compute_frame_field_detailed(const Mesh& mesh, const FieldOptions& options, ProgressSink& progress) {
  FrameFieldResult r;
  const int nf = mesh.num_faces();
  progress.report("field", 0.0, "principal curvature frames");
  r.curvature = principal_curvature_frames(mesh, options.curvature);                                      // 5.1.1
  const FrameField curvature_field = cross_field_with_straightest_matching(mesh, r.curvature.direction);  // (5.1)
  r.stability = stability_weights(mesh, r.curvature, field_curvature(mesh, curvature_field));             // (5.2)

  progress.report("field", 0.3, "feature alignment and propagation");
  const FeatureConstraints features = feature_constraints(mesh, options.features);
  r.constrained = features.constrained;
  Eigen::VectorXcd X = r.curvature.direction;
  for (int t = 0; t < nf; ++t)
    if (r.constrained[static_cast<std::size_t>(t)]) X[t] = features.direction[t];
  r.trusted = select_trusted(mesh, r.stability, options.trusted_fraction, r.constrained);
  // A (5.4) of the smoothing does not depend on the filled field: it is factored on another core while the fill
  // runs (on a 1M-face mesh the two factorizations take about equally long). Same result as one after the other.
  std::unique_ptr<FrameSmoother> smoother;
  auto factor_smoothing = [&] {
    if (options.smoothing_rounds > 0 && !progress.cancelled())
      smoother = std::make_unique<FrameSmoother>(mesh, r.stability, r.trusted, r.constrained, options.lambda);
  };
  if (options.fill == Fill::Propagate) {
    factor_smoothing();
    X = propagate_frames(mesh, X, r.trusted, r.stability);  // 5.1.2
  } else {
    const PowerFieldProblem problem = power_fill_problem(r, X, options);
    tbb::parallel_invoke([&] { X = smooth_power_field(mesh, problem).X; }, factor_smoothing);
    for (int t = 0; t < nf; ++t)  // bit-exact curve directions (the solve returns them normalized once more)
      if (r.constrained[static_cast<std::size_t>(t)]) X[t] = features.direction[t];
  }
  r.field = cross_field_with_straightest_matching(mesh, X);
  r.energy_smooth_initial = r.energy_smooth = smoothing_energy(mesh, r.field);
  if (!progress.cancelled() && smoother) smooth_field(mesh, options, *smoother, r, progress);
  if (options.split_singularities && !progress.cancelled()) split_singularities(mesh, options, smoother, r);
  progress.report("field", 0.9, "indices");
  r.branch_points = branch_points(mesh, r.field);
  progress.report("field", 1.0, "done");
  return r;
}

FrameField compute_frame_field(const Mesh& mesh, const FieldOptions& options, ProgressSink& progress) {
  return compute_frame_field_detailed(mesh, options, progress).field;
}

}  // namespace quadcover
