// The QuadCover pipeline on the covering (thesis 2.4, 4.1-4.2).
#include "param/parameterize.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "calculus/sparse_cholesky.h"
#include "common/errors.h"
#include "common/quarter_turn.h"
#include "common/side_by_side.h"
#include "cover/complex_stiffness.h"
#include "field/feature_alignment.h"
#include "field/indices.h"
#include "param/alignment.h"
#include "param/cone_separation.h"
#include "param/cover_cut.h"
#include "param/curve_rounding.h"
#include "param/disk_functions.h"
#include "param/even_branch_fix.h"
#include "param/face_count.h"
#include "param/harmonic_correction.h"
#include "param/period_matrix.h"
#include "param/ring_winding.h"
#include "param/stiffening.h"
#include "param/untangle.h"

namespace quadcover {

namespace {

/// Per component of M: true iff the gauged matching is ≡ 0 mod 4 on all its interior edges (trivial holonomy, no
/// branch points): then covering constants are in the kernel of 𝔏̄ and 𝔏̄*, and one value per component is pinned.
std::vector<char> trivial_holonomy(const Mesh& mesh, const CoverCut& cc) {
  std::vector<char> trivial(static_cast<std::size_t>(mesh.num_components()), 1);
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (!mesh.is_boundary_edge(e) && mod4(cc.matching[e]) != 0)
      trivial[mesh.face_component()[mesh.EF()(e, 0)]] = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (cc.branch[v]) trivial[mesh.vertex_component()[v]] = 0;
  return trivial;
}

/// J∇v per face for a covering nonconforming function v (reference gauge): J∇ψ_e = e / A.
FramePairs rotated_gradient(const Mesh& mesh, const Eigen::MatrixX3i& mu, const Eigen::VectorXcd& v) {
  FramePairs G = FramePairs::Zero(mesh.num_faces(), 2);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Complex w = ipow(mu(f, k)) * v[mesh.FE()(f, k)];
      const Complex e = mesh.edge_vector_local(f, k) / mesh.face_areas()[f];
      G(f, 0) += w.real() * e;
      G(f, 1) += w.imag() * e;
    }
  return G;
}

/// Period-matrix rounding (6.3) of the free paths' periods: x = T z with z integer and T the lattice basis in real
/// coordinates (x = (Re d, Im d) per free path, see param/period_matrix.h).
struct PeriodRounding {
  bool active = false;
  PeriodMatrix pm;
  std::vector<int> variable_of_path;  ///< per path: its index in pm.paths, or -1 (dependent path)
  /// E_H = xᵀ P x of the rounded periods `rounded` of the periods `periods`.
  double energy(const std::vector<Complex>& periods, const std::vector<Complex>& rounded) const {
    const int m = static_cast<int>(pm.paths.size());
    Eigen::VectorXd x(2 * m);
    for (int a = 0; a < m; ++a) {
      const Complex d = rounded[pm.paths[a]] - periods[pm.paths[a]];
      x[a] = d.real();
      x[m + a] = d.imag();
    }
    return x.dot(pm.P * x);
  }
};

/// Rounds the free periods with options.rounding (P.rounded_periods holds the direct rounding on entry).
/// Cancellation (progress.cancelled()) keeps the direct rounding or the search's best periods so far.
PeriodRounding round_with_period_matrix(const Mesh& mesh, const CoverCut& cc, const HarmonicCorrection& correction,
                                        const ParamOptions& options, ProgressSink& progress, Parameterization& P) {
  PeriodRounding r;
  r.variable_of_path.assign(static_cast<std::size_t>(cc.num_paths()), -1);
  if (options.rounding.strategy == RoundingStrategy::Direct) return r;
  const std::function<bool()> stop = [&progress] { return progress.skip_improvements(); };
  r.pm = period_matrix(mesh, cc, correction, 0, stop);
  P.diagnostics.rounding.stopped_early = progress.skip_improvements();
  const int m = static_cast<int>(r.pm.paths.size());
  if (m == 0) return r;
  r.active = true;
  for (int a = 0; a < m; ++a) r.variable_of_path[r.pm.paths[a]] = a;
  P.diagnostics.rounding.variables = 2 * m;
  P.diagnostics.rounding.period_matrix_asymmetry = r.pm.asymmetry;
  P.diagnostics.rounding.energy_direct = r.energy(P.periods, P.rounded_periods);
  const Eigen::MatrixXd T = lattice_basis(options.lattice, m);
  Eigen::VectorXd beta(2 * m);
  for (int a = 0; a < m; ++a) {
    beta[a] = P.periods[r.pm.paths[a]].real();
    beta[m + a] = P.periods[r.pm.paths[a]].imag();
  }
  RoundingResult rr;
  RoundingOptions ro = options.rounding;
  ro.stop = stop;
  try {
    rr = round_periods(T.transpose() * r.pm.P * T, T.partialPivLu().solve(beta), ro);
  } catch (const NumericalError&) {
    P.diagnostics.rounding.energy_rounded = P.diagnostics.rounding.energy_direct;  // singular P: keep the direct rounding
    return r;
  }
  const Eigen::VectorXd x = T * rr.c.cast<double>();
  for (int a = 0; a < m; ++a) P.rounded_periods[r.pm.paths[a]] = Complex(x[a], x[m + a]);
  P.diagnostics.rounding.strategy = to_string(rr.used);
  P.diagnostics.rounding.candidates = rr.candidates;
  P.diagnostics.rounding.proven_optimal = rr.proven_optimal;
  P.diagnostics.rounding.stopped_early = rr.stopped_early;
  P.diagnostics.rounding.energy_rounded = r.energy(P.periods, P.rounded_periods);
  return r;
}

/// The close branch point pairs the rounding put on one point, and with `step` separate_cones
/// (param/cone_separation.h): its steps are priced by E_H when the period matrix rounded the periods, by
/// Σ|c_j − b_j|² otherwise.
void separate_close_cones(const Mesh& mesh, const CoverCut& cc, const Eigen::VectorXcd& c,
                          const PeriodRounding& rounding, const ParamOptions& options, bool step, Parameterization& P) {
  std::vector<char> free_path(static_cast<std::size_t>(cc.num_paths()), 1);
  for (int j = 0; j < cc.num_paths(); ++j)
    free_path[j] = rounding.active
                       ? rounding.variable_of_path[j] >= 0
                       : std::find(cc.dependent_path.begin(), cc.dependent_path.end(), j) == cc.dependent_path.end();
  const auto energy = [&](const std::vector<Complex>& rounded) {
    if (rounding.active) return rounding.energy(P.periods, rounded);
    double sum = 0;
    for (std::size_t j = 0; j < rounded.size(); ++j) sum += std::norm(rounded[j] - P.periods[j]);
    return sum;
  };
  const SeparationProblem problem{mesh, cc, c, P.periods, std::move(free_path), options.lattice, energy};
  auto& diagnostics = P.diagnostics.rounding;
  if (!step) {
    for (const ConePair& pair : coincident_cones(problem, P.rounded_periods))
      diagnostics.coincident_cones.emplace_back(pair.p, pair.q);
    diagnostics.coincident_cone_pairs_left = static_cast<int>(diagnostics.coincident_cones.size());
    return;
  }
  const SeparationResult r = separate_cones(problem, P.rounded_periods);
  for (const ConePair& pair : r.coincident) diagnostics.coincident_cones.emplace_back(pair.p, pair.q);
  diagnostics.coincident_cone_pairs_left = r.left;
  for (const ConePair& pair : r.set_apart) diagnostics.separated_cones.emplace_back(pair.p, pair.q);
  if (r.steps > 0 && rounding.active) diagnostics.energy_rounded = rounding.energy(P.periods, P.rounded_periods);
}

}  // namespace

/// The steps of parameterize() that report progress (its calls of lap()).
constexpr double kParamSteps = 11;

namespace {

/// The stage meter of parameterize(): one lap per step into P.diagnostics.stage_seconds and .stage_peak_bytes, and one
/// progress bar for the whole stage, in the order of its steps (kParamSteps of them, numbered by the laps).
class StageLaps {
 public:
  StageLaps(Parameterization& P, ProgressSink& progress) : P_(P), progress_(progress) {}
  /// Begins the next step here (the time since the last lap is not recorded).
  void restart() { meter_.restart(); }
  void operator()(const char* stage) {
    meter_.lap(stage, P_.diagnostics.stage_seconds, P_.diagnostics.stage_peak_bytes);
    progress_.report("param", std::min(1.0, static_cast<double>(P_.diagnostics.stage_seconds.size()) / kParamSteps), stage);
  }

 private:
  Parameterization& P_;
  ProgressSink& progress_;
  StageMeter meter_;
};

/// Step 1 (4.2): the cut through B and the gauge; records the cut, the gauge, the branch points and h_sym in P.
CoverCut cut_and_gauge(const Mesh& mesh, const FrameField& field, Parameterization& P) {
  CoverCut cc = build_cover_cut(mesh, field.matching);
  P.cut_edges = cc.graph.cut;
  P.face_rotation = cc.face_rotation;
  {
    // Reported by the cross-field index (Def. 3.3, Σ = χ, the cone angle 2π(1 − q/4) of the map); the matching index
    // of the covering (Def. 3.2) agrees with it mod 4, which is all the covering needs.
    const Eigen::VectorXi q = cross_field_quarter_index(mesh, field);
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (cc.branch[v]) P.branch_points.push_back({v, q[v]});
  }
  P.h_sym = cc.h_sym();
  return cc;
}

/// The closed components whose holonomy is not trivial although they have no branch point.
std::vector<int> holonomy_without_branch_points(const Mesh& mesh, const std::vector<char>& trivial,
                                                const std::vector<BranchPoint>& branch_points) {
  std::vector<int> components;
  std::vector<char> has_branch(trivial.size(), 0);
  for (const BranchPoint& bp : branch_points) has_branch[mesh.vertex_component()[bp.vertex]] = 1;
  for (int comp = 0; comp < mesh.num_components(); ++comp)
    if (!trivial[comp] && !has_branch[comp] && mesh.components()[comp].boundary_loops == 0) components.push_back(comp);
  return components;
}

/// The gauged frames Z, scaled so that one grid unit is h along the RMS-normalized field (sets P.edge_length
/// and P.scale), h / ρ on a component of density factor ρ (DensityOptions::component_density). \throw InputError if the
/// field is zero or not finite.
FramePairs scaled_frames(const Mesh& mesh, const FrameField& field, const CoverCut& cc, const ParamOptions& options,
                         Parameterization& P) {
  const int nf = mesh.num_faces();
  double rms = 0;
  for (int f = 0; f < nf; ++f) rms += mesh.face_areas()[f] * 0.5 * (std::norm(field.X[f]) + std::norm(field.Y[f]));
  rms = std::sqrt(rms / mesh.total_area());
  if (!(rms > 0) || !std::isfinite(rms)) throw InputError("", 0, "parameterize: the frame field is zero or not finite");
  P.edge_length = target_edge_length(mesh, options.density, static_cast<int>(P.branch_points.size()));
  P.scale = 1.0 / (P.edge_length * rms);
  P.component_density = options.density.component_density;
  const Eigen::VectorXd rho = face_density(mesh, P.component_density);  // 1 on one component
  FramePairs Z(nf, 2);
  for (int f = 0; f < nf; ++f) {
    const auto [x, y] = turn_frame(field.X[f], field.Y[f], cc.face_rotation[f]);
    Z(f, 0) = rho[f] * P.scale * x;
    Z(f, 1) = rho[f] * P.scale * y;
  }
  return Z;
}

/// With a requested quad count N (DensityOptions::target_quads, no edge length), the first h = sqrt(area / N) makes
/// Z cover N unit squares, but the curl removal takes area off the free map X̂ (2-12 % on the shipped meshes at
/// N = 6500). Steps 1-3 are linear in 1/h, so the free map is scaled instead by the k that gives it N expected
/// faces: k²A + k L / 2 = N (A its parameter area, L its slanted boundary length, param/face_count.h). The rounding
/// then moves the count by about 1 %. Where k would change the area by more than kMaxCountFit, the free map is no
/// guide (on a disk of a dozen triangles around one cone it has no area: the rounded periods make the whole map)
/// and h stays. \return k (1 without a requested count). \pre free_map #F by 3: the corner values of step 3
double count_fitting_scale(const Mesh& mesh, const Eigen::MatrixX3cd& free_map, const DensityOptions& density) {
  constexpr double kMaxCountFit = 1.5, kSlantRadians = 0.05;
  if (density.target_quads <= 0 || density.edge_length > 0) return 1.0;
  const double area = parameter_area(mesh, free_map);
  const double half_boundary = 0.5 * slanted_boundary_length(mesh, free_map, kSlantRadians);
  const double n = density.target_quads;
  const double k = (std::sqrt(half_boundary * half_boundary + 4 * area * n) - half_boundary) / (2 * area);
  return area > 0 && std::isfinite(k) && k * k <= kMaxCountFit && k * k >= 1 / kMaxCountFit ? k : 1.0;
}

/// Step 2: curl removal on the covering, 𝔏̄* v = -curl* Z̃; returns X̃_C = J∇v (X̂ = Z − X̃_C). 𝔏̄ (#V, for steps
/// 4-5) is factored into `harmonic` beside or after it.
FramePairs remove_curl(const Mesh& mesh, const CoverCut& cc, const std::vector<char>& trivial, const FramePairs& Z,
                       std::optional<HarmonicCorrection>& harmonic) {
  const int ne = mesh.num_edges();
  Eigen::SparseMatrix<Complex> Ls = complex_nonconforming_stiffness(mesh, cc.matching);
  Eigen::VectorXcd rhs = -complex_curl_star(mesh, FrameField{Z.col(0), Z.col(1), cc.matching});
  {
    // Dirichlet condition v = 0 on boundary edges: {J∇v : v|∂M = 0} is exactly the orthogonal complement of the
    // fields that are curl*-free at interior edges, so X̂ is their L²-closest element and J∇v ⟂ every gradient.
    // On closed components with trivial holonomy one edge is pinned against the constant kernel.
    std::vector<int> pinned;
    std::vector<char> done(trivial.size(), 0);
    for (int e = 0; e < ne; ++e) {
      const int c = mesh.face_component()[mesh.face_of_edge(e)];
      if (mesh.is_boundary_edge(e) || (trivial[c] && !done[c] && mesh.components()[c].boundary_loops == 0)) {
        done[c] = 1;
        pinned.push_back(e);
        rhs[e] = 0;
      }
    }
    pin_rows(Ls, pinned);
  }
  // The two factorizations are independent (each sequential: the result does not depend on the thread count). On
  // large meshes one after the other, 𝔏̄*'s factor freed after its one solve before 𝔏̄ is factored.
  Eigen::VectorXcd v;
  const auto curl_removal = [&] {
    SparseCholesky<Complex> chol_s;
    chol_s.compute(Ls, "curl removal (complex nonconforming stiffness)");
    Ls = Eigen::SparseMatrix<Complex>();  // not needed for the solve
    v = chol_s.solve(rhs);
  };
  run_side_by_side(mesh.num_faces(), curl_removal, [&] { harmonic.emplace(mesh, cc, trivial); });
  return rotated_gradient(mesh, edge_layers(mesh, cc.matching), v);
}

/// Step 4, first part: the constant of each component fixes its dependent path at no cost (shifts φ and c).
void round_dependent_paths(const Mesh& mesh, const CoverCut& cc, Lattice lattice, Eigen::VectorXcd& phi,
                           Eigen::VectorXcd& c) {
  for (int comp = 0; comp < mesh.num_components(); ++comp) {
    const int j0 = cc.dependent_path[comp];
    if (j0 < 0) continue;
    const int e0 = cc.path_edge[j0];
    const Complex w = (round_to_lattice(c[e0], lattice) - c[e0]) / (Complex(1) - ipow(cc.rotation[e0]));
    for (int i = 0; i < cc.disk.num_vertices(); ++i)
      if (mesh.vertex_component()[cc.disk.original_vertex[i]] == comp) phi[i] += w;
    for (int e = 0; e < mesh.num_edges(); ++e)
      if (cc.graph.cut[e] && mesh.face_component()[mesh.EF()(e, 0)] == comp)
        c[e] += (Complex(1) - ipow(cc.rotation[e])) * w;
  }
}

/// The lines of the aligned curves (null: no curves) and φ̂ per corner, for the rounding with the lines.
struct CurveLines {
  const AlignedLines* aligned = nullptr;
  const Eigen::MatrixX3cd& known_free;
};

/// The rounding with the lines (param/curve_rounding.h) into P and `given`; false if it did not run (off, no line
/// worth it, direct rounding, or too large), and the period matrix rounds alone. \throw InputError if
/// options.alignment.free_line_vertices names a vertex the mesh does not have.
bool round_periods_with_lines(const Mesh& mesh, const CoverCut& cc, const HarmonicCorrection& correction,
                              const CurveLines& lines, const ParamOptions& options, Parameterization& P,
                              std::optional<GivenLines>& given) {
  if (!lines.aligned || !options.alignment.round_with_periods || options.rounding.strategy == RoundingStrategy::Direct)
    return false;
  std::vector<char> left_free;
  if (!options.alignment.free_line_vertices.empty()) {
    std::vector<char> flags(static_cast<std::size_t>(mesh.num_vertices()), 0);
    for (const int v : options.alignment.free_line_vertices) {
      if (v < 0 || v >= mesh.num_vertices())
        throw InputError("", 0,
                         "parameterize: free_line_vertices names vertex " + std::to_string(v) + " of " +
                             std::to_string(mesh.num_vertices()));
      flags[v] = 1;
    }
    left_free = lines.aligned->lines_touching(flags);
  }
  const CurveRoundingInputs in{cc,        correction,        *lines.aligned, lines.known_free,
                               P.periods, P.rounded_periods, P.edge_length,  face_density(mesh, P.component_density),
                               left_free};
  const CurveRounding r =
      round_with_curves(mesh, in, options.lattice, options.rounding, options.alignment.limits.min_length);
  if (!r.active) return false;
  for (std::size_t a = 0; a < r.paths.size(); ++a) P.rounded_periods[r.paths[a]] = r.periods[a];
  given = GivenLines{r.lines, r.line_values, std::move(left_free)};
  auto& diag = P.diagnostics.rounding;
  diag.strategy = to_string(r.search.used);
  diag.variables = r.variables;
  diag.candidates = r.search.candidates;
  diag.proven_optimal = r.search.proven_optimal;
  diag.energy_direct = r.energy_direct;
  diag.energy_rounded = r.energy_rounded;
  diag.curve_conditions = r.conditions;
  diag.curve_conditions_met = r.conditions_met;
  diag.curve_lines = static_cast<int>(std::count(r.lines.begin(), r.lines.end(), 1));
  return true;
}

/// Step 4 (4.2.2, 6.3): the periods of the translations c, their rounding (direct, then with the period matrix,
/// then the even branch point fix-up) into P; returns the translation change d per edge. With the curves' lines
/// (`lines.aligned` not null) and options.alignment.round_with_periods, the periods and the lines' integers are
/// rounded together instead of with the period matrix (param/curve_rounding.h); `given` then receives the lines and
/// their integers.
Eigen::VectorXcd round_periods_of(const Mesh& mesh, const CoverCut& cc, const HarmonicCorrection& correction,
                                  const Eigen::VectorXcd& c, const CurveLines& lines, const ParamOptions& options,
                                  ProgressSink& progress, StageLaps& lap, Parameterization& P,
                                  std::optional<GivenLines>& given) {
  const int n = cc.num_paths();
  P.periods.resize(n);
  P.rounded_periods.resize(n);
  for (int j = 0; j < n; ++j) {
    P.periods[j] = c[cc.path_edge[j]];
    P.rounded_periods[j] = round_to_lattice(P.periods[j], options.lattice);
  }
  // The factor of 𝔏̄ serves the period matrix (6.3.2) and the final harmonic correction.
  lap("harmonic_factor");
  PeriodRounding rounding;
  if (!round_periods_with_lines(mesh, cc, correction, lines, options, P, given))
    rounding = round_with_period_matrix(mesh, cc, correction, options, progress, P);
  if (rounding.active || given) lap("period_rounding");
  if (options.lattice == Lattice::Rotated && options.fix_even_branch_points && cc.b_even > 0) {
    // The parity step with the smallest E_H (period matrix) or, without it, the smallest |d_j|.
    P.diagnostics.unfixed_even_branch_points = fix_even_branch_points(mesh, cc, P.rounded_periods, [&](int j) {
      return rounding.active && rounding.variable_of_path[j] >= 0 ? rounding.energy(P.periods, P.rounded_periods)
                                                                  : std::abs(P.rounded_periods[j] - P.periods[j]);
    });
  }
  // Not with the curves' integers rounded with the periods: a step would break their closing conditions.
  separate_close_cones(mesh, cc, c, rounding, options, options.separate_close_cones && !given, P);
  Eigen::VectorXcd d = Eigen::VectorXcd::Zero(mesh.num_edges());
  for (int j = 0; j < n; ++j) d[cc.path_edge[j]] = P.rounded_periods[j] - P.periods[j];
  complete_translations(mesh, cc, d);
  lap("round");
  return d;
}

/// ½‖X̃ − ∇φ̃‖² − E_D for a correction u: ∇φ − Z = (Σ̃_d − X̃_C) − ∇u, and X̃_C is orthogonal to both gradients.
double correction_energy(const Mesh& mesh, const HarmonicCorrection& correction, const FramePairs& Sigma,
                         const Eigen::VectorXcd& u) {
  return frame_norm2(mesh, Sigma - corner_gradient(mesh, correction.corner_values(u)));
}

/// The boundary and feature edges the field is aligned with (param/alignment.h), none when alignment is off.
std::vector<CurveSlot> curve_slots(const Mesh& mesh, const FramePairs& Z, const ParamOptions& options) {
  if (!options.alignment.enabled) return {};
  const FeatureConstraints features = feature_constraints(mesh, options.features);
  return aligned_curve_slots(mesh, Z, features.feature_edges, options.alignment.tolerance_degrees);
}

/// The inputs of the refinements of the harmonic correction u (beyond the thesis).
struct CorrectionInputs {
  const HarmonicCorrection& correction;
  AlignedCorrection* aligned;      ///< the curve constraints, or null
  const Eigen::MatrixX3cd& known;  ///< φ = known − u
  const FramePairs& Z;             ///< the scaled gauged frames
  const FramePairs& Sigma;         ///< Σ̃_d
  const FramePairs& XC;            ///< X̃_C
  const Eigen::VectorXi& cone_index;  ///< per vertex, the field's cross-field quarter index (the map's cone angles)
};

/// Relaxation, local stiffening and untangling of the correction u, with their energies into P.
void refine_correction(const Mesh& mesh, const CoverCut& cc, const CorrectionInputs& in, const ParamOptions& options,
                       ProgressSink& progress, StageLaps& lap, Parameterization& P, Eigen::VectorXcd& u) {
  const HarmonicCorrection& correction = in.correction;
  AlignedCorrection* const aligned = in.aligned;
  // Relaxation rounds with flipped triangles and local stiffening re-solve with weighted 𝔏̄_w u = b_w, with the
  // curve constraints if there are any; they keep the pattern and reuse the symbolic analysis.
  SparseCholesky<Complex> weighted_chol;
  const WeightedCorrectionSolve solve = [&](const Eigen::SparseMatrix<Complex>& Lw, const Eigen::VectorXcd& bw,
                                            bool refactorize) {
    if (aligned) return aligned->solve(Lw, bw, refactorize);
    if (refactorize) {
      Eigen::SparseMatrix<Complex> Lp = Lw;
      pin_rows(Lp, correction.kernel_pins());
      weighted_chol.factorize(Lp, "weighted harmonic correction");
    }
    Eigen::VectorXcd bp = bw;
    for (int p : correction.kernel_pins()) bp[p] = 0;
    return Eigen::VectorXcd(weighted_chol.solve(bp));
  };
  // What the weighted solves of the stiffening follow: ∇φ ≈ Z, or the relaxed targets.
  FramePairs followed_gradient = in.Z, followed_target = in.Sigma - in.XC;
  if (options.relaxation.iterations > 0) {
    // The unweighted matrix is factored already: the relaxation rounds only re-solve.
    const CorrectionResolve resolve = [&](const Eigen::VectorXcd& bw) -> Eigen::VectorXcd {
      if (aligned) return aligned->solve(correction.stiffness(), bw, /*refactorize=*/false);
      return correction.solve(bw).col(0);
    };
    RelaxedCorrection relaxed = relax_correction(mesh, cc.matching, correction, in.known, in.Z, 1.0 / P.edge_length,
                                                 face_density(mesh, P.component_density), u, resolve, solve,
                                                 options.relaxation, progress, P.diagnostics.relaxation);
    u = std::move(relaxed.u);
    followed_gradient = std::move(relaxed.gradient_target);
    followed_target = std::move(relaxed.target);
    // ≥ 0: u_free minimizes it (round-off aside)
    P.diagnostics.relaxation.energy = correction_energy(mesh, correction, in.Sigma, u) - P.energy_harmonic;
    if (P.diagnostics.relaxation.iterations > 0) lap("relaxation");
  }
  if (options.stiffening.max_iterations > 0) {
    u = stiffen_correction(mesh, cc.matching, correction, in.known, followed_gradient, followed_target, u, solve,
                           options.stiffening, progress, P.diagnostics.stiffening);
    if (P.diagnostics.stiffening.kept_iteration > 0)
      P.diagnostics.stiffening.energy = correction_energy(mesh, correction, in.Sigma, u) - P.energy_harmonic - P.diagnostics.relaxation.energy;
    if (P.diagnostics.stiffening.iterations > 0) lap("stiffening");
  }
  // The seamless affine subspace: the kernel pins (or the curve constraints, which include them) fixed.
  const std::vector<char> releasable = aligned ? aligned->fixed_components() : std::vector<char>{};
  const std::vector<char> fixed = untangle_fixed_components(
      mesh, correction.layers(), aligned ? std::vector<int>{} : correction.kernel_pins(), releasable);
  P.subspace = {correction.layers().layer, correction.layers().branch, fixed};
  if (options.untangle.enabled) {
    const double price_before = correction_energy(mesh, correction, in.Sigma, u);
    u = untangle_and_rewind(mesh, correction.layers(), in.known, in.Z, fixed, u, in.cone_index, options.untangle,
                            progress, P.diagnostics.untangling, releasable);
    if (P.diagnostics.untangling.iterations > 0) {
      P.diagnostics.untangling.energy = correction_energy(mesh, correction, in.Sigma, u) - price_before;
      lap("untangling");
    }
    const int nv = mesh.num_vertices();
    for (int p : P.diagnostics.untangling.released_vertices)  // curve constraints given up there
      for (const int i : {p, nv + p})
        if (releasable[i] && !correction.layers().branch[p]) P.subspace.fixed[i] = 0;
  }
}

/// Step 6: the transitions of the final map φ = P.uv across the cut edges: rotation k_e and the Gaussian integer
/// nearest to its translation (the residual into P.max_translation_residual).
void assemble_transitions(const Mesh& mesh, const CoverCut& cc, Parameterization& P) {
  const int ne = mesh.num_edges();
  const Eigen::VectorXcd cfinal = cut_translations(mesh, cc, P.uv);
  P.transition_rotation = Eigen::VectorXi::Zero(ne);
  P.transition_translation = Eigen::VectorXcd::Zero(ne);
  for (int e = 0; e < ne; ++e) {
    if (!cc.graph.cut[e]) continue;
    P.transition_rotation[e] = cc.rotation[e];
    P.transition_translation[e] = round_to_lattice(cfinal[e], Lattice::Unit);
    P.diagnostics.max_translation_residual =
        std::max(P.diagnostics.max_translation_residual, std::abs(cfinal[e] - P.transition_translation[e]));
  }
}

}  // namespace

/// What steps 1-5 leave for the rest: heap-held, so the laps and the curve constraints may point into it.
struct SolvedMap::State {
  State(const Mesh& m, const FrameField& f, const ParamOptions& o, ProgressSink& p)
      : mesh(m), field(f), options(o), progress(p), lap(P, p) {}
  const Mesh& mesh;
  const FrameField& field;
  const ParamOptions options;
  ProgressSink& progress;
  Parameterization P;
  StageLaps lap;
  CoverCut cc;
  FramePairs Z, XC, Sigma;
  std::optional<HarmonicCorrection> harmonic;
  Eigen::MatrixX3cd known;  ///< φ = known − u
  std::optional<AlignedCorrection> aligned;
  Eigen::VectorXcd u;
};

namespace {

/// Steps 1-5 of parameterize() into s.
void solve_steps(SolvedMap::State& s) {
  const Mesh& mesh = s.mesh;
  const ParamOptions& options = s.options;
  Parameterization& P = s.P;
  // ---- 1. cut through B and gauge (4.2)
  s.cc = cut_and_gauge(mesh, s.field, P);
  const CoverCut& cc = s.cc;
  const std::vector<char> trivial = trivial_holonomy(mesh, cc);
  P.diagnostics.holonomy_without_branch_points = holonomy_without_branch_points(mesh, trivial, P.branch_points);
  s.lap("cut");
  s.Z = scaled_frames(mesh, s.field, cc, options, P);

  // ---- 2. curl removal on the covering: 𝔏̄* v = -curl* Z̃, X̂ = Z - J∇v
  s.XC = remove_curl(mesh, cc, trivial, s.Z, s.harmonic);
  const FramePairs Xhat = s.Z - s.XC;
  P.energy_curl = frame_norm2(mesh, s.XC);
  s.lap("curl_removal");

  // ---- 3. integration over the cut disk and the periods
  Eigen::VectorXcd phi = integrate_on_disk(mesh, cc, Xhat);
  const Eigen::MatrixX3cd free_corners = corner_values(cc, phi);
  Eigen::VectorXcd c = cut_translations(mesh, cc, free_corners, &P.diagnostics.integration_mismatch);
  if (const double k = count_fitting_scale(mesh, free_corners, options.density); k != 1.0) {
    s.Z *= k, s.XC *= k, phi *= k, c *= k;
    P.edge_length /= k, P.scale *= k, P.energy_curl *= k * k, P.diagnostics.integration_mismatch *= k;
  }
  s.lap("integrate");

  // ---- 4. rounding (4.2.2)
  round_dependent_paths(mesh, cc, options.lattice, phi, c);
  const HarmonicCorrection& correction = *s.harmonic;  // factored during the curl removal
  const std::vector<CurveSlot> slots = curve_slots(mesh, s.Z, options);
  const Eigen::MatrixX3cd known_free = corner_values(cc, phi);
  std::optional<AlignedLines> aligned_lines;
  if (!slots.empty()) aligned_lines.emplace(mesh, cc, correction.layers().layer, slots);
  std::optional<GivenLines> given;
  const Eigen::VectorXcd d =
      round_periods_of(mesh, cc, correction, c, {aligned_lines ? &*aligned_lines : nullptr, known_free}, options,
                       s.progress, s.lap, P, given);

  // ---- 5. harmonic correction H̃_d = Σ̃_d - (Σ̃_d)_P: 𝔏̄ u = -div Σ̃_d with branch rows removed
  const Eigen::MatrixX3cd sigma = jump_function(mesh, cc, d);
  s.Sigma = corner_gradient(mesh, sigma);
  const Eigen::VectorXcd b = correction.rhs(s.Sigma);
  const Eigen::VectorXcd u_free = correction.solve(b).col(0);
  // With curves, every later solve is the aligned one: the factor of 𝔏̄ goes before that one is made.
  if (!slots.empty()) s.harmonic->release_factor();
  s.known = known_free + sigma;
  // Boundary and feature curves on integer iso-lines: one real component of u fixed at every curve vertex.
  if (!slots.empty())
    s.aligned.emplace(mesh, cc, correction.layers().layer, s.known, u_free, correction.kernel_pins(), slots,
                      options.alignment.limits, given ? &*given : nullptr);
  s.u = s.aligned ? s.aligned->solve(correction.stiffness(), b) : u_free;
  P.energy_harmonic = correction_energy(mesh, correction, s.Sigma, s.u);
  s.lap("harmonic");
}

}  // namespace

SolvedMap::SolvedMap(const Mesh& mesh, const FrameField& field, const ParamOptions& options, ProgressSink& progress) {
  if (field.X.size() != mesh.num_faces() || field.Y.size() != mesh.num_faces() ||
      field.matching.size() != mesh.num_edges())
    throw InputError("", 0, "parameterize: the frame field does not match the mesh");
  state_ = std::make_unique<State>(mesh, field, options, progress);
  solve_steps(*state_);
}

SolvedMap::~SolvedMap() = default;
SolvedMap::SolvedMap(SolvedMap&&) noexcept = default;
SolvedMap& SolvedMap::operator=(SolvedMap&&) noexcept = default;

double SolvedMap::energy_curl() const { return state_->P.energy_curl; }
double SolvedMap::energy_harmonic() const { return state_->P.energy_harmonic; }
int SolvedMap::h_sym() const { return state_->P.h_sym; }
double SolvedMap::scale() const { return state_->P.scale; }

Parameterization SolvedMap::finish() && {
  if (!state_) throw InputError("", 0, "SolvedMap::finish: the map was finished already");
  State& s = *state_;
  s.lap.restart();  // time spent elsewhere since the solve is not this map's
  const HarmonicCorrection& correction = *s.harmonic;
  const Eigen::VectorXi cone_index = cross_field_quarter_index(s.mesh, s.field);
  const CorrectionInputs inputs{correction, s.aligned ? &*s.aligned : nullptr, s.known, s.Z, s.Sigma, s.XC, cone_index};
  refine_correction(s.mesh, s.cc, inputs, s.options, s.progress, s.lap, s.P, s.u);
  if (s.aligned) {
    s.P.aligned_curves = s.aligned->curves(s.u);
    s.P.diagnostics.alignment_conflicts = s.aligned->conflicts();
  }

  // ---- 6. φ = φ̂ + σ - u: the integral of X̂ + H̃_d with the rounded periods
  s.P.uv = s.known - correction.corner_values(s.u);
  assemble_transitions(s.mesh, s.cc, s.P);
  s.lap("assemble");
  Parameterization P = std::move(s.P);
  state_.reset();
  return P;
}

Parameterization parameterize(const Mesh& mesh, const FrameField& field, const ParamOptions& options,
                              ProgressSink& progress) {
  return SolvedMap(mesh, field, options, progress).finish();
}

}  // namespace quadcover
