// Alignment of boundary and feature curves to integer iso-lines with a constrained harmonic correction.
#include "param/alignment.h"

#include <cmath>
#include <map>
#include <numbers>
#include <numeric>

#include "calculus/sparse_cholesky.h"
#include "common/quarter_turn.h"
#include "cover/complex_stiffness.h"

namespace quadcover {

std::vector<CurveSlot> aligned_curve_slots(const Mesh& mesh, const FramePairs& Z, const std::vector<int>& feature_edges,
                                           double tolerance_degrees) {
  std::vector<int> candidates = feature_edges;
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (mesh.is_boundary_edge(e)) candidates.push_back(e);
  const double tol = std::sin(tolerance_degrees * std::numbers::pi / 180);
  std::vector<CurveSlot> slots;
  for (const int e : candidates) {
    const int f = mesh.face_of_edge(e);
    int k = 0;
    while (mesh.FE()(f, k) != e) ++k;
    const Complex d = mesh.edge_vector_local(f, k) / std::abs(mesh.edge_vector_local(f, k));
    for (int a = 0; a < 2; ++a) {
      const Complex along = Z(f, 1 - a);  // the frame vector that should run along the curve
      if (std::abs(along) == 0) continue;
      if (std::abs(std::imag(std::conj(d) * along)) < tol * std::abs(along)) {
        slots.push_back({e, f, a});
        break;
      }
    }
  }
  return slots;
}

namespace {

// What the slots of AlignedCorrection are read against: the map φ = known - i^layer u (branch vertices: known).
struct SlotFrame {
  const Mesh& mesh;
  const CoverCut& cut;
  const Eigen::MatrixX3i& layer;
  const Eigen::MatrixX3cd& known;
  const std::vector<CurveSlot>& slots;

  Complex phi_at(const Eigen::VectorXcd& u, int f, int c) const {
    const int p = mesh.F()(f, c);
    return known(f, c) - (cut.branch[p] ? Complex(0) : ipow(layer(f, c)) * u[p]);
  }
  /// Corner of slot i's face at the end `end` of its edge.
  int corner(int i, int end) const { return mesh.corner_of(slots[i].face, mesh.E()(slots[i].edge, end)); }
};

// One end of a slot at a vertex p: the component of u_p it fixes.
struct Use {
  int slot, corner_face, corner;
  int component;  // 0: x, 1: y of u_p
  int sign;       // u-component = sign · β
};

double known_coord(const SlotFrame& s, const Use& w) {
  return std::real(ipow(-s.slots[w.slot].coordinate) * s.known(w.corner_face, w.corner));
}

// Each slot i (a curve edge) asks coordinate a_i = n_i at both endpoints; at a vertex p this fixes one real
// component of u_p: Re(i^{-s} u_p) = Re(i^{-a} known) - n, s = a - λ (s even: x = ±β, s odd: y = ±β).
std::vector<std::vector<Use>> slot_uses(const SlotFrame& s) {
  std::vector<std::vector<Use>> uses(static_cast<std::size_t>(s.mesh.num_vertices()));
  for (int i = 0; i < static_cast<int>(s.slots.size()); ++i)
    for (int end = 0; end < 2; ++end) {
      const int f = s.slots[i].face, c = s.corner(i, end), p = s.mesh.F()(f, c);
      if (s.cut.branch[p]) continue;  // pinned by the periods (integral on the rotated and coarse lattices)
      const int q = mod4(s.slots[i].coordinate - s.layer(f, c));
      uses[p].push_back({i, f, c, q % 2, (q == 0 || q == 1) ? 1 : -1});
    }
  return uses;
}

// n_j = σ n_i + τ between two slots that fix one component of one u_p.
struct Rel {
  int to, sigma;
  double tau;
};

// Every two uses of one component of one u_p by different slots i, j (vertex order, then use order), with
// σ = sign_i sign_j: the slot graph of AlignedLines and of the relations below.
template <class Visit>
void for_each_slot_pair(const std::vector<std::vector<Use>>& uses, Visit visit) {
  for (const auto& at : uses)
    for (std::size_t a = 0; a < at.size(); ++a)
      for (std::size_t b = a + 1; b < at.size(); ++b)
        if (at[a].component == at[b].component && at[a].slot != at[b].slot)
          visit(at[a], at[b], at[a].sign * at[b].sign);
}

// Relations: u-comp = sign_i (K_i - n_i) = sign_j (K_j - n_j)  =>  n_j = σ n_i + τ, σ = sign_i sign_j,
// τ = K_j - σ K_i.
std::vector<std::vector<Rel>> slot_relations(const SlotFrame& s, const std::vector<std::vector<Use>>& uses) {
  std::vector<std::vector<Rel>> rel(s.slots.size());
  for_each_slot_pair(uses, [&](const Use& wi, const Use& wj, int sigma) {
    const double tau = std::round(known_coord(s, wj) - sigma * known_coord(s, wi));
    rel[wi.slot].push_back({wj.slot, sigma, tau});
    rel[wj.slot].push_back({wi.slot, sigma, -sigma * tau});  // n_i = σ n_j - σ τ
  });
  return rel;
}

constexpr const char* kTwoIntegers = "two branch points at different integers";
constexpr const char* kClosesOtherwise = "closes on itself with another integer";
constexpr const char* kMeetsOtherwise = "meets another line at another integer";

// Left free because the rounded periods allow no integer iso-line there (not by a CurveLimits limit).
bool cannot_be_iso_line(const AlignedCurve& c) {
  return !c.enforced && (c.left_free_because == kTwoIntegers || c.left_free_because == kClosesOtherwise ||
                         c.left_free_because == kMeetsOtherwise);
}

// Per slot: its curve and n = σ n_root + τ.
struct SlotCurves {
  std::vector<int> curve_of, sigma_of;
  std::vector<double> tau_of;
};

// The breadth-first search over the relations from `root`: adds curve k (slots, value, enforced) to `curves`.
// The root value is the rounded mean of the unconstrained solution u0 along the whole line.
void trace_curve(const SlotFrame& s, const std::vector<std::vector<Rel>>& rel, const Eigen::VectorXcd& u0,
                 const CurveLimits& limits, const GivenLines* given, int root, std::vector<AlignedCurve>& curves,
                 SlotCurves& sc) {
  const int k = static_cast<int>(curves.size());
  curves.push_back({});
  curves.back().coordinate = s.slots[root].coordinate;
  sc.curve_of[root] = k;
  std::vector<int> queue(1, root);
  double sum = 0, anchor = 0, length = 0, lo = INFINITY, hi = -INFINITY;
  int count = 0;
  bool anchored = false;   // a branch point on the line fixes its value (its position is set by the periods)
  bool consistent = true;  // two branch points on one line at different integers: the line cannot be kept
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int i = queue[q];
    const CurveSlot& slot = s.slots[i];
    curves[k].edges.push_back(slot.edge);
    length += std::abs(s.phi_at(u0, slot.face, s.corner(i, 1)) - s.phi_at(u0, slot.face, s.corner(i, 0)));
    for (int end = 0; end < 2; ++end) {  // estimate of n_root from slot i: σ_i (coordinate - τ_i)
      const int c = s.corner(i, end);
      const double estimate =
          sc.sigma_of[i] * (std::real(ipow(-slot.coordinate) * s.phi_at(u0, slot.face, c)) - sc.tau_of[i]);
      sum += estimate;
      lo = std::min(lo, estimate), hi = std::max(hi, estimate);
      ++count;
      if (s.cut.branch[s.mesh.F()(slot.face, c)]) {
        if (anchored && std::abs(estimate - anchor) > 0.5) consistent = false;
        if (!anchored) anchored = true, anchor = estimate;
      }
    }
    for (const Rel& r : rel[i]) {
      if (sc.curve_of[r.to] >= 0) continue;
      sc.curve_of[r.to] = k;
      sc.sigma_of[r.to] = r.sigma * sc.sigma_of[i];
      sc.tau_of[r.to] = r.sigma * sc.tau_of[i] + r.tau;
      queue.push_back(r.to);
    }
  }
  const bool chosen = given && given->lines[k];  // the rounding chose its integer with the periods
  curves[k].value = chosen ? given->values[k] : std::round(anchored ? anchor : sum / count);
  // Lines the rounding would move far (typically two close parallel features snapping to one integer, which
  // collapses the strip between them), lines far from straight in the free map (pinning bends the map across a
  // whole quad or more: the crease rim of a closed-up organic scan) and lines shorter than `min_length` (fragments
  // of noisy creases) stay free: the distortion of pinning them is worth more than the alignment.
  const double shift = std::abs(sum / count - curves[k].value);
  // A line the rounding chose is pinned whatever its shift and spread on the free map: the periods were rounded for
  // it, and the constrained energy they minimized is what pinning it costs.
  // A line the job freed (CurveAlignmentOptions::free_line_vertices) that would have been pinned says so first.
  const bool freed = given && !given->freed.empty() && given->freed[k] && length >= limits.min_length;
  const char* because = freed                         ? "freed: the map with it pinned was not valid there"
                        : !consistent                 ? kTwoIntegers
                        : chosen                      ? ""
                        : length < limits.min_length  ? "shorter than the minimum length"
                        : shift > limits.max_shift    ? "too far from an integer"
                        : hi - lo > limits.max_spread ? "wiggles more than the maximum spread"
                        : given                       ? "not rounded with the periods"
                                                      : "";
  curves[k].left_free_because = because;
  curves[k].enforced = curves[k].left_free_because.empty();
}

// Slots fixing the same component of the same u_p lie on one iso-line seen through the transitions of the cut:
// every connected set of relations is one curve.
SlotCurves trace_curves(const SlotFrame& s, const std::vector<std::vector<Rel>>& rel, const Eigen::VectorXcd& u0,
                        const CurveLimits& limits, const GivenLines* given, std::vector<AlignedCurve>& curves) {
  const int ns = static_cast<int>(s.slots.size());
  SlotCurves sc{std::vector<int>(ns, -1), std::vector<int>(ns, 1), std::vector<double>(ns, 0.0)};
  for (int root = 0; root < ns; ++root)
    if (sc.curve_of[root] < 0) trace_curve(s, rel, u0, limits, given, root, curves, sc);
  return sc;
}

// n per slot from its curve's value; the curves' edge lists in slot order with their coordinates and values.
std::vector<double> slot_values(const SlotFrame& s, const SlotCurves& sc, std::vector<AlignedCurve>& curves) {
  const int ns = static_cast<int>(s.slots.size());
  std::vector<double> n_of(static_cast<std::size_t>(ns), 0);
  for (auto& c : curves) c.edges.clear();
  for (int i = 0; i < ns; ++i) {
    n_of[i] = sc.sigma_of[i] * curves[sc.curve_of[i]].value + sc.tau_of[i];
    AlignedCurve& c = curves[sc.curve_of[i]];
    c.edges.push_back(s.slots[i].edge);
    c.edge_coordinates.push_back(s.slots[i].coordinate);
    c.edge_values.push_back(n_of[i]);
  }
  return n_of;
}

// A line that closes on itself with another integer (a boundary loop around branch points, a line through a
// cut whose transition does not map it to itself) fixes some component of u twice with different values: such
// lines, and those through two branch points at different integers, are left free (reported, not enforced).
// Returns the number of enforced curves so dropped.
int drop_conflicting_curves(const SlotFrame& s, const std::vector<std::vector<Use>>& uses,
                            const std::vector<int>& curve_of, const std::vector<double>& n_of,
                            std::vector<AlignedCurve>& curves) {
  const int nv = s.mesh.num_vertices();
  int conflicts = 0;
  std::map<int, std::pair<int, double>> seen;  // u-component index -> (curve, value)
  for (int p = 0; p < nv; ++p)
    for (const Use& w : uses[p]) {
      const int idx = w.component * nv + p, k = curve_of[w.slot];
      const double v = w.sign * (known_coord(s, w) - n_of[w.slot]);
      auto [it, inserted] = seen.try_emplace(idx, k, v);
      if (!inserted && std::abs(it->second.second - v) > 1e-9 * (1 + std::abs(v))) {
        if (curves[k].enforced) ++conflicts;
        const int other = it->second.first;
        const char* because = other == k ? kClosesOtherwise : kMeetsOtherwise;
        // A reason that no limit could lift replaces one that a limit gave.
        for (const int c : {k, other})
          if (curves[c].enforced || !cannot_be_iso_line(curves[c]))
            curves[c].enforced = false, curves[c].left_free_because = because;
      }
    }
  return conflicts;
}

}  // namespace

// Constant kernel on trivial-holonomy components (x and y decouple there): pin what no constraint fixes.
void pin_kernel(const Mesh& mesh, const std::vector<int>& kernel_pins, std::vector<char>& fixed,
                Eigen::VectorXd& value) {
  const int nv = mesh.num_vertices();
  for (const int p : kernel_pins) {
    const int comp = mesh.vertex_component()[p];
    bool has[2] = {false, false};
    for (int q = 0; q < nv; ++q)
      if (mesh.vertex_component()[q] == comp) has[0] |= fixed[q] != 0, has[1] |= fixed[nv + q] != 0;
    for (int part = 0; part < 2; ++part)
      if (!has[part]) fixed[part * nv + p] = 1, value[part * nv + p] = 0;
  }
}

AlignedLines::AlignedLines(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3i& layer,
                           std::vector<CurveSlot> slots)
    : mesh_(&mesh), slots_(std::move(slots)) {
  const Eigen::MatrixX3cd no_values;  // the structure does not read known
  const quadcover::SlotFrame frame{mesh, cut, layer, no_values, slots_};
  const int ns = static_cast<int>(slots_.size()), nv = mesh.num_vertices();
  std::vector<std::vector<int>> at_slot(static_cast<std::size_t>(ns));  // relations leaving each slot
  const std::vector<std::vector<quadcover::Use>> uses = slot_uses(frame);
  for (int p = 0; p < nv; ++p)
    for (const quadcover::Use& w : uses[p])
      uses_.push_back({w.slot, w.corner_face, w.corner, w.component * nv + p, w.sign});
  for_each_slot_pair(uses, [&](const quadcover::Use& wa, const quadcover::Use& wb, int sigma) {
    at_slot[wa.slot].push_back(static_cast<int>(relations_.size()));
    relations_.push_back({wa.slot, wb.slot, sigma, wa.corner_face, wa.corner, wb.corner_face, wb.corner});
    at_slot[wb.slot].push_back(static_cast<int>(relations_.size()));
    relations_.push_back({wb.slot, wa.slot, sigma, wb.corner_face, wb.corner, wa.corner_face, wa.corner});
  });
  trace_lines(mesh, cut, at_slot);
}

std::vector<double> AlignedLines::line_lengths(const Eigen::VectorXd& face_weight) const {
  std::vector<double> lengths(static_cast<std::size_t>(num_lines_), 0.0);
  for (const int i : order_) {  // in the order of the trace
    const double weight = face_weight.size() ? face_weight[slots_[i].face] : 1.0;
    lengths[line_of_[i]] += mesh_->edge_lengths()[slots_[i].edge] * weight;
  }
  return lengths;
}

void AlignedLines::trace_lines(const Mesh& mesh, const CoverCut& cut, const std::vector<std::vector<int>>& at_slot) {
  const int ns = static_cast<int>(slots_.size());
  parent_.assign(static_cast<std::size_t>(ns), -1);
  sigma_of_.assign(static_cast<std::size_t>(ns), 0);
  line_of_.assign(static_cast<std::size_t>(ns), -1);
  std::vector<char> tree(relations_.size(), 0);
  for (int root = 0; root < ns; ++root) {
    if (sigma_of_[root] != 0) continue;
    const int line = num_lines_++;
    sigma_of_[root] = 1;
    std::vector<Anchor> anchors;
    const std::size_t start = order_.size();
    order_.push_back(root);
    for (std::size_t q = start; q < order_.size(); ++q) {
      const int i = order_[q];
      line_of_[i] = line;
      for (int end = 0; end < 2; ++end) {
        const int f = slots_[i].face, c = mesh.corner_of(f, mesh.E()(slots_[i].edge, end));
        if (cut.branch[mesh.F()(f, c)]) anchors.push_back({i, f, c});
      }
      for (const int r : at_slot[i]) {
        const Relation& rel = relations_[r];
        if (sigma_of_[rel.to] != 0) continue;
        sigma_of_[rel.to] = rel.sigma * sigma_of_[i];
        parent_[rel.to] = r;
        tree[r] = 1;
        order_.push_back(rel.to);
      }
    }
    usable_.push_back(1);
    if (!anchors.empty()) {
      anchors_.push_back(std::move(anchors));
      line_anchor_.push_back(line);
    }
  }
  std::vector<char> fixes(static_cast<std::size_t>(num_lines_), 0);
  for (const Use& w : uses_) fixes[line_of_[w.slot]] = 1;
  for (int k = 0; k < num_lines_; ++k) usable_[k] = fixes[k];
  for (int r = 0; r < static_cast<int>(relations_.size()); ++r) {
    const Relation& rel = relations_[r];
    // Each relation is stored both ways: one residual per pair, none for the tree's own relations.
    if (tree[r] || tree[r ^ 1] || rel.from > rel.to) continue;
    if (sigma_of_[rel.to] == rel.sigma * sigma_of_[rel.from])
      closing_.push_back(r);
    else
      usable_[line_of_[rel.from]] = 0;  // the line comes back reversed: it fixes its own integer, not an iso-line
  }
}

std::vector<char> AlignedLines::lines_touching(const std::vector<char>& vertex_flags) const {
  std::vector<char> touching(static_cast<std::size_t>(num_lines_), 0);
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const int e = slots_[i].edge;
    if (vertex_flags[mesh_->E()(e, 0)] || vertex_flags[mesh_->E()(e, 1)]) touching[line_of_[i]] = 1;
  }
  return touching;
}

double AlignedLines::coordinate(int slot, int face, int corner, const Eigen::MatrixX3cd& known) const {
  return std::real(ipow(-slots_[slot].coordinate) * known(face, corner));
}

std::vector<double> AlignedLines::tau_along(const Eigen::MatrixX3cd& known) const {
  std::vector<double> tau_of(slots_.size(), 0.0);  // n_slot = σ n_root + τ, in the order of the tree
  for (const int i : order_)
    if (parent_[i] >= 0) {
      const Relation& rel = relations_[parent_[i]];
      tau_of[i] = rel.sigma * tau_of[rel.from] + relation_tau(rel, known);
    }
  return tau_of;
}

double AlignedLines::relation_tau(const Relation& rel, const Eigen::MatrixX3cd& known) const {
  return coordinate(rel.to, rel.face_to, rel.corner_to, known) -
         rel.sigma * coordinate(rel.from, rel.face_from, rel.corner_from, known);
}

double AlignedLines::root_value(const Anchor& a, const std::vector<double>& tau_of,
                                const Eigen::MatrixX3cd& known) const {
  return sigma_of_[a.slot] * (coordinate(a.slot, a.face, a.corner, known) - tau_of[a.slot]);
}

Eigen::VectorXd AlignedLines::line_residuals(const Eigen::MatrixX3cd& known, const Eigen::VectorXd& n,
                                             const std::vector<char>& lines) const {
  const std::vector<double> tau_of = tau_along(known);
  std::vector<double> r;
  for (const int k : closing_) {
    const Relation& rel = relations_[k];
    if (lines[line_of_[rel.from]])
      r.push_back(tau_of[rel.to] - rel.sigma * tau_of[rel.from] - relation_tau(rel, known));
  }
  for (std::size_t j = 0; j < anchors_.size(); ++j)
    if (lines[line_anchor_[j]])
      for (const Anchor& a : anchors_[j]) r.push_back(n[line_anchor_[j]] - root_value(a, tau_of, known));
  return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

std::vector<char> AlignedLines::fixed_components(const std::vector<char>& lines) const {
  std::vector<char> fixed(static_cast<std::size_t>(2 * mesh_->num_vertices()), 0);
  for (const Use& w : uses_)
    if (lines[line_of_[w.slot]]) fixed[w.index] = 1;
  return fixed;
}

Eigen::VectorXd AlignedLines::fixed_values(const Eigen::MatrixX3cd& known, const Eigen::VectorXd& n,
                                           const std::vector<char>& lines) const {
  const std::vector<double> tau_of = tau_along(known);
  Eigen::VectorXd value = Eigen::VectorXd::Zero(2 * mesh_->num_vertices());
  for (const Use& w : uses_) {
    const int line = line_of_[w.slot];
    if (!lines[line]) continue;
    const double n_slot = sigma_of_[w.slot] * n[line] + tau_of[w.slot];
    value[w.index] = w.sign * (coordinate(w.slot, w.face, w.corner, known) - n_slot);
  }
  return value;
}

AlignedCorrection::AlignedCorrection(const Mesh& mesh, const CoverCut& cut, const Eigen::MatrixX3i& layer,
                                     const Eigen::MatrixX3cd& known, const Eigen::VectorXcd& u0,
                                     const std::vector<int>& kernel_pins, const std::vector<CurveSlot>& slots,
                                     const CurveLimits& limits, const GivenLines* given)
    : mesh_(&mesh), cut_(&cut), layer_(&layer), known_(&known), slots_(slots) {
  const SlotFrame frame{mesh, cut, layer, known, slots_};
  const int nv = mesh.num_vertices();
  const std::vector<std::vector<Use>> uses = slot_uses(frame);
  SlotCurves sc = trace_curves(frame, slot_relations(frame, uses), u0, limits, given, curves_);
  n_of_ = slot_values(frame, sc, curves_);
  curve_of_ = std::move(sc.curve_of);
  conflicts_ = drop_conflicting_curves(frame, uses, curve_of_, n_of_, curves_);
  fixed_.assign(static_cast<std::size_t>(2 * nv), 0);
  value_ = Eigen::VectorXd::Zero(2 * nv);
  for (int p = 0; p < nv; ++p)
    for (const Use& w : uses[p]) {
      if (!curves_[curve_of_[w.slot]].enforced) continue;
      const int idx = w.component * nv + p;
      fixed_[idx] = 1;
      value_[idx] = w.sign * (known_coord(frame, w) - n_of_[w.slot]);
    }
  pin_kernel(mesh, kernel_pins, fixed_, value_);
}

ConstrainedSolve::ConstrainedSolve(std::vector<char> fixed) : fixed_(std::move(fixed)) {
  free_id_.assign(fixed_.size(), -1);
  for (std::size_t i = 0; i < fixed_.size(); ++i)
    if (!fixed_[i]) free_id_[i] = free_count_++;
}

void ConstrainedSolve::factorize(const Eigen::SparseMatrix<Complex>& L) {
  // Real form of the Hermitian system: L = A + iB acts on [x; y] as [[A, -B], [B, A]].
  const int nv = static_cast<int>(L.rows());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(4 * L.nonZeros()));
  const auto add = [&](int r, int c, double v) {
    if (v != 0 && free_id_[r] >= 0 && free_id_[c] >= 0) trip.emplace_back(free_id_[r], free_id_[c], v);
  };
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(L, col); it; ++it) {
      const int p = static_cast<int>(it.row()), q = static_cast<int>(it.col());
      const double A = it.value().real(), B = it.value().imag();
      add(p, q, A), add(p, nv + q, -B), add(nv + p, q, B), add(nv + p, nv + q, A);
    }
  Eigen::SparseMatrix<double> M(free_count_, free_count_);
  M.setFromTriplets(trip.begin(), trip.end());
  // The first analysis orders the vertices of 𝔏̄ by nested dissection (its pattern is the mesh's for every
  // matching: one ordering per mesh for the whole job), each vertex's free x and y side by side. CHOLMOD's own
  // choice on the real graph of 2·#V took 2-3× longer with METIS's time (BENCHMARKS.md, "Ordering the aligned
  // correction"). Later calls with the same pattern only refactorize.
  constexpr int kOrderedSize = 1000;
  std::vector<int> ordering;
  if (chol_.rows() == 0)
    for (const int p : nested_dissection_ordering(L, kOrderedSize))
      for (const int idx : {p, nv + p})
        if (free_id_[idx] >= 0) ordering.push_back(free_id_[idx]);
  chol_.factorize(M, "aligned harmonic correction", ordering);
}

Eigen::MatrixXcd ConstrainedSolve::solve(const Eigen::SparseMatrix<Complex>& L, const Eigen::MatrixXcd& B,
                                         const Eigen::MatrixXd& values) const {
  const int nv = static_cast<int>(L.rows()), k = static_cast<int>(B.cols());
  Eigen::MatrixXd rhs(free_count_, k);
  for (int i = 0; i < nv; ++i) {
    if (free_id_[i] >= 0) rhs.row(free_id_[i]) = B.row(i).real();
    if (free_id_[nv + i] >= 0) rhs.row(free_id_[nv + i]) = B.row(i).imag();
  }
  const auto move_fixed = [&](int r, int c, double v) {  // the fixed column's term to the right-hand side
    if (v != 0 && free_id_[r] >= 0 && free_id_[c] < 0) rhs.row(free_id_[r]) -= v * values.row(c);
  };
  for (int col = 0; col < L.outerSize(); ++col)
    for (Eigen::SparseMatrix<Complex>::InnerIterator it(L, col); it; ++it) {
      const int p = static_cast<int>(it.row()), q = static_cast<int>(it.col());
      const double A = it.value().real(), B = it.value().imag();
      move_fixed(p, q, A), move_fixed(p, nv + q, -B), move_fixed(nv + p, q, B), move_fixed(nv + p, nv + q, A);
    }
  const Eigen::MatrixXd sol = chol_.solve(rhs);
  Eigen::MatrixXcd u(nv, k);
  for (int p = 0; p < nv; ++p)
    for (int j = 0; j < k; ++j) {
      const double x = free_id_[p] >= 0 ? sol(free_id_[p], j) : values(p, j);
      const double y = free_id_[nv + p] >= 0 ? sol(free_id_[nv + p], j) : values(nv + p, j);
      u(p, j) = Complex(x, y);
    }
  return u;
}

Eigen::VectorXcd AlignedCorrection::solve(const Eigen::SparseMatrix<Complex>& L, const Eigen::VectorXcd& b,
                                          bool refactorize) {
  if (!solver_) solver_.emplace(fixed_);
  if (refactorize || !factored_) solver_->factorize(L);
  factored_ = true;
  return solver_->solve(L, b, value_).col(0);
}

std::vector<AlignedCurve> AlignedCorrection::curves(const Eigen::VectorXcd& u) const {
  const Mesh& mesh = *mesh_;
  std::vector<AlignedCurve> curves = curves_;
  const int ns = static_cast<int>(slots_.size());
  const std::vector<CurveSlot>& slots = slots_;
  const std::vector<int>& curve_of = curve_of_;
  const std::vector<double>& n_of = n_of_;
  auto phi_at = [&](int f, int c) {
    const int p = mesh.F()(f, c);
    return (*known_)(f, c) - (cut_->branch[p] ? Complex(0) : ipow((*layer_)(f, c)) * u[p]);
  };
  // Deviation of every curve from its iso-line on the result (all curve vertices, branch points included).
  for (int i = 0; i < ns; ++i)
    for (int end = 0; end < 2; ++end) {
      const int c = mesh.corner_of(slots[i].face, mesh.E()(slots[i].edge, end));
      const double x = std::real(ipow(-slots[i].coordinate) * phi_at(slots[i].face, c));
      AlignedCurve& curve = curves[curve_of[i]];
      curve.max_deviation = std::max(curve.max_deviation, std::abs(x - n_of[i]));
    }
  return curves;
}

}  // namespace quadcover
