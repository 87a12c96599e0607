#include "param/cone_separation.h"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <limits>
#include <unordered_map>

#include "common/quarter_turn.h"
#include "mesh/vertex_rings.h"
#include "param/disk_functions.h"
#include "param/lattice.h"

namespace quadcover {

namespace {

/// Crossings of a shortest path of faces from `from` to `to` over interior edges (breadth first, work proportional
/// to the faces explored), empty when to == from or `to` is not reached.
std::vector<FanCrossing> face_path(const Mesh& mesh, int from, int to) {
  std::unordered_map<int, FanCrossing> reached_by{{from, FanCrossing{-1, from, -1}}};
  std::deque<int> queue{from};
  while (!queue.empty() && !reached_by.count(to)) {
    const int f = queue.front();
    queue.pop_front();
    for (int k = 0; k < 3; ++k) {
      const int e = mesh.FE()(f, k);
      if (mesh.is_boundary_edge(e)) continue;
      const int g = mesh.EF()(e, 0) == f ? mesh.EF()(e, 1) : mesh.EF()(e, 0);
      if (reached_by.emplace(g, FanCrossing{f, g, e}).second) queue.push_back(g);
    }
  }
  std::vector<FanCrossing> path;
  if (!reached_by.count(to)) return path;
  for (int f = to; f != from; f = reached_by.at(f).from) path.push_back(reached_by.at(f));
  return {path.rbegin(), path.rend()};
}

/// The cut translations of jumps d given on the paths' edges, completed (linear in d).
Eigen::VectorXcd completed(const Mesh& mesh, const CoverCut& cut, const std::vector<Complex>& jump) {
  Eigen::VectorXcd d = Eigen::VectorXcd::Zero(mesh.num_edges());
  for (int j = 0; j < cut.num_paths(); ++j) d[cut.path_edge[j]] = jump[j];
  complete_translations(mesh, cut, d);
  return d;
}

/// One lattice step in each of the four directions.
std::vector<Complex> lattice_steps(Lattice lattice) {
  switch (lattice) {
    case Lattice::Unit:
      return {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    case Lattice::Coarse:
      return {{2, 0}, {-2, 0}, {0, 2}, {0, -2}};
    default:
      return {{1, 1}, {-1, -1}, {-1, 1}, {1, -1}};
  }
}

/// Offsets below this are one point (branch points sit on lattice points, or half-integers for unfixed even ones).
constexpr double kSamePoint = 0.25;

int count_coincident(const std::vector<Complex>& offsets) {
  int n = 0;
  for (const Complex& z : offsets) n += std::abs(z) < kSamePoint;
  return n;
}

}  // namespace

Complex branch_point_image(const Mesh& mesh, const CoverCut& cut, const Eigen::VectorXcd& T, int v) {
  const auto [K, D] = transition_around(mesh, cut, T, v);
  return K == 0 ? Complex(0) : D / (Complex(1) - ipow(K));
}

ConePairOffset::ConePairOffset(const Mesh& mesh, const CoverCut& cut, ConePair pair)
    : mesh_(&mesh), cut_(&cut), pair_(pair) {
  path_ = face_path(mesh, fan_crossings(mesh, pair.p).front().from, fan_crossings(mesh, pair.q).front().from);
}

Complex ConePairOffset::operator()(const Eigen::VectorXcd& T) const {
  // z ↦ i^k z + t carries p's chart along the path into the chart of q's first fan face.
  Complex t = 0;
  int k = 0;
  for (const FanCrossing& cr : path_) {
    t = carry_across(*mesh_, *cut_, T, cr, t);
    k += crossing_rotation(*mesh_, *cut_, cr);
  }
  const Complex q_there = branch_point_image(*mesh_, *cut_, T, pair_.q);
  return (q_there - t) * ipow(-k) - branch_point_image(*mesh_, *cut_, T, pair_.p);
}

Eigen::VectorXcd rounded_translations(const SeparationProblem& problem, const std::vector<Complex>& rounded) {
  std::vector<Complex> jump(rounded.size());
  for (std::size_t j = 0; j < rounded.size(); ++j) jump[j] = rounded[j] - problem.periods[j];
  return problem.continuous + completed(problem.mesh, problem.cut, jump);
}

std::vector<ConePair> close_branch_points(const Mesh& mesh, const CoverCut& cut, int rings) {
  std::vector<ConePair> pairs;
  const auto interior_branch = [&](int v) { return cut.branch[v] && !mesh.is_boundary_vertex(v); };
  for (int p = 0; p < mesh.num_vertices(); ++p) {
    if (!interior_branch(p)) continue;
    std::vector<int> near;
    for (const int f : faces_within_rings(mesh, p, rings))
      for (int k = 0; k < 3; ++k)
        if (const int q = mesh.F()(f, k); q > p && interior_branch(q)) near.push_back(q);
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (const int q : near) pairs.push_back({p, q});
  }
  return pairs;
}

namespace {

/// Linear functions of the rounded periods the separation watches: the close pairs' offsets, and the images of the
/// even branch points (on integer points after param/even_branch_fix.h; a step must not move one off).
struct Watched {
  std::vector<ConePair> pairs;  ///< of `offset`
  std::vector<Complex> offset, even_image;
  /// Per free path: how one unit of its period moves each offset and each even image (empty for fixed paths).
  std::vector<std::vector<Complex>> offset_move, even_move;

  int coincident() const { return count_coincident(offset); }
  int even_off_lattice() const {
    int n = 0;
    for (const Complex& z : even_image) n += distance_to_gaussian_integers(z) > kSamePoint;
    return n;
  }
  /// The watched values after `step` on path j.
  Watched stepped(int j, Complex step) const {
    Watched w{pairs, offset, even_image, {}, {}};
    for (std::size_t k = 0; k < offset.size(); ++k) w.offset[k] += offset_move[j][k] * step;
    for (std::size_t k = 0; k < even_image.size(); ++k) w.even_image[k] += even_move[j][k] * step;
    return w;
  }
};

/// The watched values of `rounded`, with their moves when `with_moves` and a pair is on one point.
Watched watch(const SeparationProblem& problem, const std::vector<Complex>& rounded, bool with_moves) {
  const Mesh& mesh = problem.mesh;
  const CoverCut& cut = problem.cut;
  Watched w;
  w.pairs = close_branch_points(mesh, cut, kWatchedRings);
  std::vector<ConePairOffset> offset_of;
  for (const ConePair& pair : w.pairs) offset_of.emplace_back(mesh, cut, pair);
  std::vector<int> even;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (cut.branch[v] && !mesh.is_boundary_vertex(v) && mod4(cut.quarter_index[v]) == 2) even.push_back(v);
  const auto values = [&](const Eigen::VectorXcd& T, std::vector<Complex>& offsets, std::vector<Complex>& images) {
    for (const ConePairOffset& o : offset_of) offsets.push_back(o(T));
    for (const int v : even) images.push_back(branch_point_image(mesh, cut, T, v));
  };
  values(rounded_translations(problem, rounded), w.offset, w.even_image);
  const int n = cut.num_paths();
  w.offset_move.resize(static_cast<std::size_t>(n));
  w.even_move.resize(static_cast<std::size_t>(n));
  if (!with_moves || w.coincident() == 0) return w;
  for (int j = 0; j < n; ++j) {
    if (!problem.free_path[j]) continue;
    std::vector<Complex> unit(static_cast<std::size_t>(n), 0);
    unit[j] = 1;
    values(completed(mesh, cut, unit), w.offset_move[j], w.even_move[j]);  // linear in the periods
  }
  return w;
}

}  // namespace

std::vector<ConePair> coincident_cones(const SeparationProblem& problem, const std::vector<Complex>& rounded) {
  const Watched w = watch(problem, rounded, false);
  std::vector<ConePair> out;
  for (std::size_t k = 0; k < w.pairs.size(); ++k)
    if (std::abs(w.offset[k]) < kSamePoint) out.push_back(w.pairs[k]);
  return out;
}

SeparationResult separate_cones(const SeparationProblem& problem, std::vector<Complex>& rounded) {
  Watched w = watch(problem, rounded, true);
  SeparationResult result;
  for (std::size_t k = 0; k < w.pairs.size(); ++k)
    if (std::abs(w.offset[k]) < kSamePoint) result.coincident.push_back(w.pairs[k]);
  const int even_off = w.even_off_lattice();
  const std::vector<Complex> first_offset = w.offset;
  for (int now = w.coincident(); now > 0;) {
    double best_energy = std::numeric_limits<double>::infinity();
    int best_path = -1;
    Complex best_step;
    for (int j = 0; j < static_cast<int>(rounded.size()); ++j) {
      if (!problem.free_path[j]) continue;
      for (const Complex& s : lattice_steps(problem.lattice)) {
        const Watched after = w.stepped(j, s);
        if (after.coincident() >= now || after.even_off_lattice() > even_off) continue;
        rounded[j] += s;
        const double e = problem.energy(rounded);
        rounded[j] -= s;
        if (e < best_energy) best_energy = e, best_path = j, best_step = s;
      }
    }
    if (best_path < 0) break;
    rounded[best_path] += best_step;
    Watched after = w.stepped(best_path, best_step);
    after.offset_move = std::move(w.offset_move);
    after.even_move = std::move(w.even_move);
    w = std::move(after);
    now = w.coincident();
    ++result.steps;
  }
  for (std::size_t k = 0; k < w.pairs.size(); ++k)
    if (std::abs(first_offset[k]) < kSamePoint && std::abs(w.offset[k]) >= kSamePoint)
      result.set_apart.push_back(w.pairs[k]);
  result.left = w.coincident();
  return result;
}

}  // namespace quadcover
