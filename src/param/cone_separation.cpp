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

}  // namespace

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

/// Values of linear functions of the rounded periods the separation watches: the close pairs' offsets, and the
/// images of the even branch points (on integer points after param/even_branch_fix.h; a step must not move one off).
struct WatchedValues {
  std::vector<Complex> offset, even_image;

  int coincident() const {
    return static_cast<int>(
        std::count_if(offset.begin(), offset.end(), [](Complex z) { return std::abs(z) < kSamePoint; }));
  }
  int even_off_lattice() const {
    return static_cast<int>(std::count_if(even_image.begin(), even_image.end(),
                                          [](Complex z) { return distance_to_gaussian_integers(z) > kSamePoint; }));
  }
};

struct Watched {
  std::vector<ConePair> pairs;  ///< of values.offset: close_branch_points(kWatchedRings)
  WatchedValues values;
  /// Per free path: the values' change for one unit of its period (empty for fixed paths).
  std::vector<WatchedValues> move;

  /// The pairs on one point.
  std::vector<ConePair> on_one_point() const {
    std::vector<ConePair> out;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (std::abs(values.offset[k]) < kSamePoint) out.push_back(pairs[k]);
    return out;
  }
  /// The values after `step` on path j.
  WatchedValues stepped(int j, Complex step) const {
    WatchedValues w = values;
    for (std::size_t k = 0; k < w.offset.size(); ++k) w.offset[k] += move[j].offset[k] * step;
    for (std::size_t k = 0; k < w.even_image.size(); ++k) w.even_image[k] += move[j].even_image[k] * step;
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
  const auto values = [&](const Eigen::VectorXcd& T) {
    WatchedValues out;
    for (const ConePairOffset& o : offset_of) out.offset.push_back(o(T));
    for (const int v : even) out.even_image.push_back(branch_point_image(mesh, cut, T, v));
    return out;
  };
  w.values = values(rounded_translations(problem, rounded));
  const int n = cut.num_paths();
  w.move.resize(static_cast<std::size_t>(n));
  if (!with_moves || w.values.coincident() == 0) return w;
  for (int j = 0; j < n; ++j) {
    if (!problem.free_path[j]) continue;
    std::vector<Complex> unit(static_cast<std::size_t>(n), 0);
    unit[j] = 1;
    w.move[j] = values(completed(mesh, cut, unit));  // linear in the periods
  }
  return w;
}

}  // namespace

std::vector<ConePair> coincident_cones(const SeparationProblem& problem, const std::vector<Complex>& rounded) {
  return watch(problem, rounded, false).on_one_point();
}

SeparationResult separate_cones(const SeparationProblem& problem, std::vector<Complex>& rounded) {
  Watched w = watch(problem, rounded, true);
  SeparationResult result;
  result.coincident = w.on_one_point();
  const int even_off = w.values.even_off_lattice();
  for (int now = w.values.coincident(); now > 0;) {
    double best_energy = std::numeric_limits<double>::infinity();
    int best_path = -1;
    Complex best_step;
    for (int j = 0; j < static_cast<int>(rounded.size()); ++j) {
      if (!problem.free_path[j]) continue;
      for (const Complex& s : lattice_steps(problem.lattice)) {
        const WatchedValues after = w.stepped(j, s);
        if (after.coincident() >= now || after.even_off_lattice() > even_off) continue;
        rounded[j] += s;
        const double e = problem.energy(rounded);
        rounded[j] -= s;
        if (e < best_energy) best_energy = e, best_path = j, best_step = s;
      }
    }
    if (best_path < 0) break;
    rounded[best_path] += best_step;
    w.values = w.stepped(best_path, best_step);
    now = w.values.coincident();
    ++result.steps;
  }
  const std::vector<ConePair> left = w.on_one_point();
  for (const ConePair& pair : result.coincident)
    if (std::none_of(left.begin(), left.end(), [&](const ConePair& l) { return l.p == pair.p && l.q == pair.q; }))
      result.set_apart.push_back(pair);
  result.left = static_cast<int>(left.size());
  return result;
}

}  // namespace quadcover
