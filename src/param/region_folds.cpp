#include "param/region_folds.h"

#include <algorithm>
#include <cmath>

#include "param/seams.h"

namespace quadcover {

RegionFolds::RegionFolds(const Mesh& mesh, const VertexLayers& layers, const Eigen::MatrixX3cd& base,
                         const std::vector<char>& stuck, const std::vector<char>& region_fixed,
                         const Eigen::VectorXd& X)
    : mesh_(&mesh), layers_(&layers), base_(&base), counted_(stuck.size()) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  total_3d_ = mesh.face_areas().sum();
  for (int f = 0; f < nf; ++f) {
    counted_[f] = !stuck[f];
    bool moves = false;
    for (int c = 0; c < 3; ++c) {
      const int p = mesh.F()(f, c);
      moves = moves || !region_fixed[p] || !region_fixed[nv + p];
    }
    if (moves) {
      moving_.push_back(f);
      continue;
    }
    const double a = signed_area(f, X), a3 = mesh.face_areas()[f];
    still_abs_ += std::abs(a);
    if (!counted_[f]) continue;
    if (a < 0 || (a3 <= 0 && a == 0))
      ++still_always_;
    else if (a3 > 0)
      still_q_.push_back(a / a3);
  }
  const double threshold = flip_tolerance * (total_3d_ > 0 ? total_uv(X) / total_3d_ : 0);
  low_ = 0.5 * threshold;
  high_ = 2 * threshold;
  for (const double q : still_q_) {
    if (q <= low_)
      ++below_band_;
    else if (q <= high_)
      band_.push_back(q);
  }
}

double RegionFolds::signed_area(int f, const Eigen::VectorXd& Y) const {
  const Eigen::Index nv = Y.size() / 2;
  Complex c[3];
  for (int a = 0; a < 3; ++a) {
    const int p = mesh_->F()(f, a);
    c[a] = (*base_)(f, a) - layered_value(*layers_, f, a, p, Complex(Y[p], Y[nv + p]));
  }
  return signed_uv_area(c[0], c[1], c[2]);
}

double RegionFolds::total_uv(const Eigen::VectorXd& Y) const {
  double total = still_abs_;
  for (const int f : moving_) total += std::abs(signed_area(f, Y));
  return total;
}

int RegionFolds::operator()(const Eigen::VectorXd& Y) const {
  std::vector<double> area(moving_.size());
  double total_uv = still_abs_;
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    area[k] = signed_area(moving_[k], Y);
    total_uv += std::abs(area[k]);
  }
  const double ratio = total_3d_ > 0 ? total_uv / total_3d_ : 0;
  const double threshold = flip_tolerance * ratio;
  const bool in_band = threshold > low_ && threshold <= high_;
  const auto at_most = [threshold](double q) { return q <= threshold; };
  int count = still_always_;
  count += in_band ? below_band_ + static_cast<int>(std::count_if(band_.begin(), band_.end(), at_most))
                   : static_cast<int>(std::count_if(still_q_.begin(), still_q_.end(), at_most));
  for (std::size_t k = 0; k < moving_.size(); ++k) {
    const int f = moving_[k];
    if (counted_[f] && non_positive_uv_area(area[k], flip_tolerance * mesh_->face_areas()[f] * ratio)) ++count;
  }
  return count;
}

}  // namespace quadcover
