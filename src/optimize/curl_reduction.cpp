#include "optimize/curl_reduction.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>

#include "common/quarter_turn.h"
#include "common/seconds_since.h"
#include "field/indices.h"

namespace quadcover {

int count_branch_points(const Mesh& mesh, const Eigen::VectorXi& q) {
  int n = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) n += !mesh.is_boundary_vertex(v) && mod4(q[v]) != 0;
  return n;
}

namespace {

class Reducer {
 public:
  Reducer(const Mesh& mesh, CurlEnergy& energy, CurlEstimator* screening, const CurlReductionOptions& options,
          ProgressSink& progress)
      : mesh_(mesh), ed_(energy), est_(screening), opt_(options), progress_(progress),
        start_(std::chrono::steady_clock::now()) {
    if (opt_.local_estimates && !est_) est_ = (own_est_ = std::make_unique<CurlEstimator>(energy)).get();
    q_ = matching_quarter_index(mesh, energy.matching());
    bp_ = count_branch_points(mesh, q_);
    // Vertex -> incident interior edges (CSR), for the breadth-first searches between branch points.
    std::vector<int> deg(mesh.num_vertices() + 1, 0);
    for (int e = 0; e < mesh.num_edges(); ++e)
      if (!mesh.is_boundary_edge(e)) ++deg[mesh.E()(e, 0) + 1], ++deg[mesh.E()(e, 1) + 1];
    std::partial_sum(deg.begin(), deg.end(), deg.begin());
    offs_ = deg;
    adj_.resize(deg.back());
    for (int e = 0; e < mesh.num_edges(); ++e)
      if (!mesh.is_boundary_edge(e)) adj_[deg[mesh.E()(e, 0)]++] = e, adj_[deg[mesh.E()(e, 1)]++] = e;
  }

  CurlReductionResult run() {
    res_.initial_energy = ed_.energy();
    res_.initial_branch_points = bp_;
    log("start");
    bool creation = opt_.allow_creation;
    cancellation();
    reduction(creation);
    while (opt_.delta_eh > 0 && !stop()) {
      const long cancelled = balancing();
      ++res_.balancing_rounds;
      if (cancelled == 0) break;
      creation = false;  // 6.4: no new branch points from now on
      reduction(creation);
      if (opt_.max_balancing_rounds > 0 && res_.balancing_rounds >= opt_.max_balancing_rounds) break;
    }
    res_.final_energy = ed_.energy();
    res_.final_branch_points = bp_;
    res_.seconds = elapsed();
    return std::move(res_);
  }

 private:
  using Path = std::vector<MatchingChange>;

  double elapsed() const { return seconds_since(start_); }
  /// The share of the budget used (evaluations or time, whichever is nearer its end; -1 without a budget).
  double budget_used() const {
    double f = -1;
    if (opt_.max_evaluations > 0) f = static_cast<double>(res_.evaluations) / static_cast<double>(opt_.max_evaluations);
    if (opt_.time_limit_seconds > 0) f = std::max(f, elapsed() / opt_.time_limit_seconds);
    return std::min(f, 1.0);
  }
  bool stop() {
    if (res_.stopped_early) return true;
    const std::string budget = opt_.max_evaluations > 0 ? " / " + std::to_string(opt_.max_evaluations) : "";
    progress_.report("optimize", budget_used(),
                     "evaluations " + std::to_string(res_.evaluations) + budget + ", E_D " +
                         std::to_string(ed_.energy()) + ", branch points " + std::to_string(bp_));
    const char* why = opt_.max_evaluations > 0 && res_.evaluations >= opt_.max_evaluations  ? "evaluations"
                      : opt_.time_limit_seconds > 0 && elapsed() >= opt_.time_limit_seconds ? "time"
                      : progress_.cancelled()                                               ? "cancelled"
                                                                                            : nullptr;
    if (why) res_.stopped_early = true, res_.stopped_by = why;
    return res_.stopped_early;
  }
  void log(const char* phase) { res_.log.push_back({res_.evaluations, ed_.energy(), bp_, res_.accepted, phase}); }
  bool is_branch(int v) const { return !mesh_.is_boundary_vertex(v) && mod4(q_[v]) != 0; }
  // Branch point count after a change set (only the endpoints of changed edges are affected).
  int branch_points_after(const Path& path) {
    int delta = 0;
    touched_.clear();
    for (const auto& c : path) {
      for (int s = 0; s < 2; ++s) {
        const int v = mesh_.E()(c.edge, s);
        if (std::find(touched_.begin(), touched_.end(), v) == touched_.end())
          touched_.push_back(v), delta -= is_branch(v);
        q_[v] += s == 0 ? c.delta : -c.delta;
      }
    }
    for (int v : touched_) delta += is_branch(v);
    undo_indices(path);
    return bp_ + delta;
  }
  // Whether a triangle at an endpoint of a changed edge has a branch point at each corner after `path`.
  bool crowds_a_triangle(const Path& path) {
    for (const auto& c : path) q_[mesh_.E()(c.edge, 0)] += c.delta, q_[mesh_.E()(c.edge, 1)] -= c.delta;
    bool crowded = false;
    for (std::size_t i = 0; i < path.size() && !crowded; ++i)
      for (int s = 0; s < 2 && !crowded; ++s)
        for (const auto& fc : mesh_.fan(mesh_.E()(path[i].edge, s)))
          if (is_branch(mesh_.F()(fc.face, 0)) && is_branch(mesh_.F()(fc.face, 1)) &&
              is_branch(mesh_.F()(fc.face, 2))) {
            crowded = true;
            break;
          }
    undo_indices(path);
    return crowded;
  }
  void undo_indices(const Path& path) {
    for (const auto& c : path) q_[mesh_.E()(c.edge, 0)] -= c.delta, q_[mesh_.E()(c.edge, 1)] += c.delta;
  }
  bool estimating() const { return opt_.local_estimates && est_; }
  // Exact E_D after `path` (full re-smoothing, CurlEnergy::evaluate): the value a commit is based on.
  double evaluate_exact(const Path& path) {
    ++res_.exact_evaluations;
    return ed_.evaluate(path);
  }
  // Screening values of candidates: local estimates in parallel (deterministic, CurlEstimator::estimate_batch), or
  // NaN when estimates are off (the caller then evaluates exactly, one at a time).
  std::vector<double> screen(const std::vector<Path>& paths) {
    std::vector<double> out(paths.size(), std::numeric_limits<double>::quiet_NaN());
    if (estimating()) {
      est_->estimate_batch(paths, out, opt_.threads);
      res_.evaluations += static_cast<long>(paths.size());
    }
    return out;
  }
  // E_D after `path` if it may be lower than `bound`, else +inf: a screened value >= bound is trusted (no exact
  // evaluation); otherwise the exact value decides (so E_D never increases over an accepted move).
  double exact_if_promising(const Path& path, double screened, double bound) {
    if (std::isnan(screened)) {
      ++res_.evaluations;
      return ed_.evaluate(path);
    }
    if (screened >= bound) return std::numeric_limits<double>::infinity();
    return evaluate_exact(path);
  }
  void accept(const Path& path, const char* phase) {
    ed_.commit();
    bp_ = branch_points_after(path);
    for (const auto& c : path) q_[mesh_.E()(c.edge, 0)] += c.delta, q_[mesh_.E()(c.edge, 1)] -= c.delta;
    ++res_.accepted;
    log(phase);
  }

  // Breadth-first search from branch point p to the k nearest branch points of opposite odd index (sum ≡ 0 mod 4);
  // each returned path moves p's charge along the edges to the partner, where both cancel (6.2.2 Cancellation).
  std::vector<Path> cancellation_paths(int p) {
    std::vector<Path> out;
    const int cp = mod4(q_[p]);
    if (cp != 1 && cp != 3) return out;
    parent_edge_.assign(mesh_.num_vertices(), -2);
    std::queue<int> queue;
    queue.push(p);
    parent_edge_[p] = -1;
    while (!queue.empty() && static_cast<int>(out.size()) < opt_.cancellation_neighbours) {
      const int u = queue.front();
      queue.pop();
      if (u != p && is_branch(u) && mod4(q_[u] + q_[p]) == 0) {
        // Walk back to p, then emit the edges from p to u carrying the charge c (δ so that the tail becomes 0).
        std::vector<int> chain;
        for (int w = u; w != p;) {
          const int e = parent_edge_[w];
          chain.push_back(e);
          w = mesh_.E()(e, 0) == w ? mesh_.E()(e, 1) : mesh_.E()(e, 0);
        }
        std::reverse(chain.begin(), chain.end());
        Path path;
        const int charge = cp == 1 ? 1 : -1;
        int at = p;
        for (int e : chain) {
          const bool forward = mesh_.E()(e, 0) == at;  // at = E(e,0): Δq(at) = +δ, else -δ
          path.push_back({e, forward ? -charge : charge});
          at = forward ? mesh_.E()(e, 1) : mesh_.E()(e, 0);
        }
        out.push_back(std::move(path));
        continue;  // do not search beyond a partner
      }
      for (int i = offs_[u]; i < offs_[u + 1]; ++i) {
        const int e = adj_[i];
        const int w = mesh_.E()(e, 0) == u ? mesh_.E()(e, 1) : mesh_.E()(e, 0);
        if (parent_edge_[w] != -2) continue;
        parent_edge_[w] = e;
        queue.push(w);
      }
    }
    return out;
  }

  std::vector<int> branch_vertices() const {
    std::vector<int> out;
    for (int v = 0; v < mesh_.num_vertices(); ++v)
      if (is_branch(v)) out.push_back(v);
    return out;
  }

  // Step 1: move each branch point to one of its k nearest partners if that lowers E_D.
  void cancellation() {
    for (int p : branch_vertices()) {
      if (stop()) return;
      if (!is_branch(p)) continue;  // cancelled earlier in this loop
      const std::vector<Path> paths = cancellation_paths(p);
      const std::vector<double> est = screen(paths);
      for (std::size_t i = 0; i < paths.size(); ++i) {
        if (stop()) return;
        const double bound = ed_.energy() * (1 + opt_.path_screening_margin);
        if (exact_if_promising(paths[i], est[i], bound) < ed_.energy()) {
          accept(paths[i], "cancellation");
          break;
        }
      }
    }
  }

  // Steps 2-3: sorted greedy matching changes until a whole pass accepts nothing.
  void reduction(bool creation) {
    const long resort_after = std::max(1L, static_cast<long>(opt_.resort_fraction * mesh_.num_edges()));
    for (bool improved = true; improved && !stop();) {
      improved = false;
      const Eigen::VectorXd share = ed_.distortion_shares();
      std::vector<int> order;
      for (int e = 0; e < mesh_.num_edges(); ++e)
        if (!mesh_.is_boundary_edge(e)) order.push_back(e);
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return share[a] > share[b]; });
      long changed = 0;
      // Candidates in sorted order, screened in batches (batch size doubles while nothing is accepted, back to
      // the minimum after an acceptance: a fixed rule, so the result does not depend on the thread count).
      std::size_t next = 0, batch = kMinBatch;
      std::vector<Path> paths;
      std::vector<std::size_t> after;  // position in `order` after each candidate
      while (next < order.size()) {
        if (stop()) return;
        paths.clear(), after.clear();
        while (next < order.size() && paths.size() < batch) {
          const int e = order[next++];
          const double theta = ed_.curvature(e);
          Path path{{e, theta > 0 ? -1 : 1}};  // m_e <- m_e - sign(θ_e)
          if (!creation && branch_points_after(path) > bp_) continue;
          if (opt_.separate_branch_points && crowds_a_triangle(path)) continue;
          paths.push_back(std::move(path));
          after.push_back(next);
        }
        const std::vector<double> est = screen(paths);
        bool accepted = false;
        for (std::size_t i = 0; i < paths.size() && !accepted; ++i) {
          if (stop()) return;
          if (exact_if_promising(paths[i], est[i], ed_.energy()) < ed_.energy()) {
            accept(paths[i], "reduction");
            improved = accepted = true;
            next = after[i];  // the rest of the batch was screened against the old state
          }
        }
        batch = accepted ? kMinBatch : std::min(2 * batch, kMaxBatch);
        if (accepted && ++changed > resort_after) break;  // go to step 2
      }
    }
  }

  // Step 4 (6.4): cancellation costs Δ_ED of all candidate pairs, then cancel in increasing order while the cost,
  // re-measured right before, stays below Δ_EH. \return number of cancelled pairs.
  long balancing() {
    struct Candidate {
      double cost;
      int p, q;
      Path path;
    };
    std::vector<Candidate> candidates;
    std::vector<Path> paths;
    std::vector<std::pair<int, int>> pairs;
    for (int p : branch_vertices()) {
      for (Path& path : cancellation_paths(p)) {
        int q = p;
        for (const auto& c : path) q = mesh_.E()(c.edge, 0) == q ? mesh_.E()(c.edge, 1) : mesh_.E()(c.edge, 0);
        if (q < p) continue;  // each pair once
        paths.push_back(std::move(path));
        pairs.emplace_back(p, q);
      }
    }
    // Costs Δ_ED for sorting only (estimates when available; every cancellation is re-checked exactly below).
    std::vector<double> est = screen(paths);
    for (std::size_t i = 0; i < paths.size(); ++i) {
      if (stop()) return 0;
      if (std::isnan(est[i])) est[i] = (++res_.evaluations, ed_.evaluate(paths[i]));
      const double cost = est[i] - ed_.energy();
      if (cost < opt_.delta_eh) candidates.push_back({cost, pairs[i].first, pairs[i].second, std::move(paths[i])});
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
    long cancelled = 0;
    for (const Candidate& c : candidates) {
      if (stop()) break;
      if (!is_branch(c.p) || !is_branch(c.q) || mod4(q_[c.p] + q_[c.q]) != 0) continue;
      if (branch_points_after(c.path) != bp_ - 2) continue;  // the path's charge no longer cancels exactly p and q
      const double cost = evaluate_exact(c.path) - ed_.energy();
      if (cost < opt_.delta_eh) {
        accept(c.path, "balancing");
        if (++cancelled == opt_.max_cancellations_per_round) break;
      }
    }
    res_.cancelled_pairs += cancelled;
    return cancelled;
  }

  static constexpr std::size_t kMinBatch = 4, kMaxBatch = 64;
  const Mesh& mesh_;
  CurlEnergy& ed_;
  std::unique_ptr<CurlEstimator> own_est_;  // when the caller gave none
  CurlEstimator* est_;
  const CurlReductionOptions& opt_;
  ProgressSink& progress_;
  std::chrono::steady_clock::time_point start_;
  Eigen::VectorXi q_;
  int bp_ = 0;
  std::vector<int> offs_, adj_, parent_edge_, touched_;
  CurlReductionResult res_;
};

}  // namespace

CurlReductionResult reduce_curl(const Mesh& mesh, CurlEnergy& energy, const CurlReductionOptions& options,
                                ProgressSink& progress, CurlEstimator* screening) {
  return Reducer(mesh, energy, screening, options, progress).run();
}

}  // namespace quadcover
