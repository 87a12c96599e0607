#include "render/canvas.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace quadcover {

Canvas::Canvas(int width, int height, int supersample, Rgb background)
    : width_(width),
      height_(height),
      ss_(std::max(1, supersample)),
      sw_(width * ss_),
      sh_(height * ss_),
      color_(static_cast<std::size_t>(sw_) * sh_ * 3),
      depth_(static_cast<std::size_t>(sw_) * sh_, std::numeric_limits<double>::infinity()) {
  for (std::size_t i = 0; i < color_.size(); i += 3) {
    color_[i] = static_cast<float>(background.r);
    color_[i + 1] = static_cast<float>(background.g);
    color_[i + 2] = static_cast<float>(background.b);
  }
}

void Canvas::fill_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           const Shader& shade, bool write_depth, double depth_offset) {
  // Work in sample coordinates; sample (i, j) sits at ((i + 0.5) / ss, (j + 0.5) / ss) output pixels.
  const double s = ss_;
  const Eigen::Vector2d a(p0.x() * s, p0.y() * s), b(p1.x() * s, p1.y() * s), c(p2.x() * s, p2.y() * s);
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (!(std::abs(area) > 1e-12) || !std::isfinite(area)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) - 0.5)));
  const int x1 = std::min(sw_ - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}) - 0.5)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) - 0.5)));
  const int y1 = std::min(sh_ - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}) - 0.5)));
  const double inv = 1.0 / area;
  for (int j = y0; j <= y1; ++j) {
    const double py = j + 0.5;
    for (int i = x0; i <= x1; ++i) {
      const double px = i + 0.5;
      // Edge functions, normalized: barycentric coordinates of the sample.
      const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) * inv;
      const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) * inv;
      const double w2 = 1.0 - w0 - w1;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const double z = w0 * p0.z() + w1 * p1.z() + w2 * p2.z() - depth_offset;
      const std::size_t k = static_cast<std::size_t>(j) * sw_ + i;
      if (!(z < depth_[k])) continue;
      if (write_depth) depth_[k] = z;
      const Rgb col = shade(Eigen::Vector3d(w0, w1, w2));
      color_[3 * k] = static_cast<float>(col.r);
      color_[3 * k + 1] = static_cast<float>(col.g);
      color_[3 * k + 2] = static_cast<float>(col.b);
      ++written_;
    }
  }
}

void Canvas::draw_line(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width, Rgb color,
                       double depth_offset) {
  Eigen::Vector2d d(b.x() - a.x(), b.y() - a.y());
  const double len = d.norm();
  if (!(len > 1e-12)) return;
  d /= len;
  // Extend by half the width at both ends (square caps) and offset sideways.
  const Eigen::Vector3d along(d.x() * width / 2, d.y() * width / 2, 0);
  const Eigen::Vector3d side(-d.y() * width / 2, d.x() * width / 2, 0);
  const Eigen::Vector3d q0 = a - along + side, q1 = a - along - side, q2 = b + along - side, q3 = b + along + side;
  const auto flat = [color](const Eigen::Vector3d&) { return color; };
  fill_triangle(q0, q1, q2, flat, false, depth_offset);
  fill_triangle(q0, q2, q3, flat, false, depth_offset);
}

void Canvas::draw_disk(const Eigen::Vector3d& center, double radius, Rgb color, double depth_offset) {
  constexpr int kSegments = 24;
  const auto flat = [color](const Eigen::Vector3d&) { return color; };
  for (int k = 0; k < kSegments; ++k) {
    const double t0 = 2 * std::numbers::pi * k / kSegments, t1 = 2 * std::numbers::pi * (k + 1) / kSegments;
    const Eigen::Vector3d u(center.x() + radius * std::cos(t0), center.y() + radius * std::sin(t0), center.z());
    const Eigen::Vector3d v(center.x() + radius * std::cos(t1), center.y() + radius * std::sin(t1), center.z());
    fill_triangle(center, u, v, flat, false, depth_offset);
  }
}

Image Canvas::resolve() const {
  Image out(width_, height_);
  const double norm = 1.0 / (ss_ * ss_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      double r = 0, g = 0, bl = 0;
      for (int j = 0; j < ss_; ++j)
        for (int i = 0; i < ss_; ++i) {
          const std::size_t k = static_cast<std::size_t>(y * ss_ + j) * sw_ + (x * ss_ + i);
          r += color_[3 * k];
          g += color_[3 * k + 1];
          bl += color_[3 * k + 2];
        }
      out.set(x, y, {r * norm, g * norm, bl * norm});
    }
  return out;
}

ViewCamera named_view(const std::string& name) {
  if (name == "front") return {0, 0};
  if (name == "side") return {90, 0};
  if (name == "top") return {0, 90};
  if (name == "back") return {180, 0};
  if (name == "bottom") return {0, -90};
  if (name == "iso") return {35, 25};
  throw std::invalid_argument("unknown view '" + name + "' (front, side, top, back, bottom, iso)");
}

Projection::Projection(const ViewCamera& camera, const Eigen::MatrixX3d& fit, int width, int height) {
  const double az = camera.azimuth_deg * std::numbers::pi / 180, el = camera.elevation_deg * std::numbers::pi / 180;
  back_ = Eigen::Vector3d(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
  // Right vector stays horizontal; at the poles it follows the azimuth so "top" has -Z (front) at the bottom.
  right_ = Eigen::Vector3d(std::cos(az), 0, -std::sin(az));
  up_ = back_.cross(right_).normalized();
  if (fit.rows() > 0) {
    const Eigen::Vector3d lo = fit.colwise().minCoeff(), hi = fit.colwise().maxCoeff();
    center_ = (lo + hi) / 2;
    radius_ = 0;
    for (Eigen::Index i = 0; i < fit.rows(); ++i)
      radius_ = std::max(radius_, (fit.row(i).transpose() - center_).norm());
  } else {
    center_.setZero();
  }
  if (!(radius_ > 0)) radius_ = 1;
  scale_ = camera.zoom * std::min(width, height) / (2 * radius_ * 1.05);
  cx_ = width / 2.0;
  cy_ = height / 2.0;
}

Eigen::Vector3d Projection::operator()(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d q = p - center_;
  return {cx_ + scale_ * q.dot(right_), cy_ - scale_ * q.dot(up_), -q.dot(back_)};
}

}  // namespace quadcover
