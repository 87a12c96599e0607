#include "field/propagation.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/errors.h"

namespace quadcover {

Eigen::VectorXd stability_weights(const Mesh& mesh, const CurvatureFrames& frames, const Eigen::VectorXd& theta) {
  const int nf = mesh.num_faces();
  Eigen::VectorXd w(nf);
  for (int t = 0; t < nf; ++t) {
    double sum = 0;
    for (int k = 0; k < 3; ++k) sum += std::abs(theta[mesh.FE()(t, k)]);
    w[t] = std::abs(frames.kappa_max[t] - frames.kappa_min[t]) * std::exp(-0.5 * sum);  // (5.2)
  }
  return w;
}

namespace {
// Face indices sorted by decreasing weight, ties by index.
std::vector<int> by_decreasing_weight(const Eigen::VectorXd& weights) {
  std::vector<int> order(static_cast<std::size_t>(weights.size()));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return weights[a] > weights[b]; });
  return order;
}
}  // namespace

std::vector<char> select_trusted(const Mesh& mesh, const Eigen::VectorXd& weights, double fraction,
                                 const std::vector<char>& always) {
  const int nf = mesh.num_faces();
  std::vector<char> trusted(static_cast<std::size_t>(nf), 0);
  for (std::size_t t = 0; t < always.size(); ++t) trusted[t] = always[t];
  const std::vector<int> order = by_decreasing_weight(weights);
  const auto count = static_cast<std::size_t>(std::ceil(std::clamp(fraction, 0.0, 1.0) * nf));
  for (std::size_t i = 0; i < count; ++i) trusted[static_cast<std::size_t>(order[i])] = 1;
  std::vector<char> has(static_cast<std::size_t>(mesh.num_components()), 0);
  for (int t = 0; t < nf; ++t)
    if (trusted[static_cast<std::size_t>(t)]) has[static_cast<std::size_t>(mesh.face_component()[t])] = 1;
  for (int t : order) {  // the first face met per component is its most stable one
    auto& h = has[static_cast<std::size_t>(mesh.face_component()[t])];
    if (!h) trusted[static_cast<std::size_t>(t)] = h = 1;
  }
  return trusted;
}

Eigen::VectorXcd propagate_frames(const Mesh& mesh, const Eigen::VectorXcd& X, const std::vector<char>& trusted,
                                  const Eigen::VectorXd& weights) {
  const int nf = mesh.num_faces();
  Eigen::VectorXcd out = X;
  std::vector<char> done(static_cast<std::size_t>(nf), 0);
  std::vector<int> queue;
  queue.reserve(static_cast<std::size_t>(nf));
  for (int t : by_decreasing_weight(weights))
    if (trusted[static_cast<std::size_t>(t)]) {
      done[static_cast<std::size_t>(t)] = 1;
      queue.push_back(t);
    }
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const int s = queue[i];
    for (int k = 0; k < 3; ++k) {
      const int t = mesh.neighbor(s, k);
      if (t < 0 || done[static_cast<std::size_t>(t)]) continue;
      const int e = mesh.FE()(s, k);
      const Complex rho = mesh.edge_transport()[e];
      out[t] = (mesh.EF()(e, 0) == s ? rho : std::conj(rho)) * out[s];  // parallel transport s -> t
      done[static_cast<std::size_t>(t)] = 1;
      queue.push_back(t);
    }
  }
  if (static_cast<int>(queue.size()) != nf)
    throw NumericalError("field propagation", std::to_string(nf - static_cast<int>(queue.size())) +
                                                  " faces unreachable from trusted faces (a component without one)");
  return out;
}

}  // namespace quadcover
