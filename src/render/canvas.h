#pragma once
// An offscreen software rasterizer: supersampled colour and depth buffers, triangles with a per-sample shading
// callback, thick lines and disks with a depth offset (so they sit on top of the surface they belong to).
// Screen coordinates are in output pixels (x right, y down); depth grows away from the viewer.
#include <Eigen/Core>
#include <functional>
#include <limits>
#include <vector>

#include "render/image.h"

namespace quadcover {

class Canvas {
 public:
  /// width × height output pixels, each sampled supersample × supersample times (antialiasing).
  /// \pre width, height >= 0 (supersample < 1 counts as 1).
  Canvas(int width, int height, int supersample, Rgb background);

  int width() const { return width_; }  ///< \pre none
  int height() const { return height_; }  ///< \pre none

  /// Called per covered sample with the barycentric coordinates (b0, b1, b2) of the sample in the triangle.
  using Shader = std::function<Rgb(const Eigen::Vector3d& barycentric)>;

  /// Fills triangle (x, y, depth) p0 p1 p2 (either orientation). Samples nearer than the stored depth are shaded
  /// and, if write_depth, stored. depth_offset is subtracted from the depth before the test (lines on surfaces).
  /// \pre none (samples outside the canvas are clipped).
  void fill_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                     const Shader& shade, bool write_depth = true, double depth_offset = 0);
  /// A line of the given width (output pixels) from a to b, depth-tested with the offset, not writing depth.
  /// \pre none (clipped).
  void draw_line(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double width, Rgb color, double depth_offset = 0);
  /// A filled disk of the given radius (output pixels), depth-tested at the centre's depth minus the offset.
  /// \pre none (clipped).
  void draw_disk(const Eigen::Vector3d& center, double radius, Rgb color, double depth_offset = 0);

  /// Number of samples written so far (for tests: coverage). \pre none
  long long samples_written() const { return written_; }

  /// The antialiased image: each output pixel is the mean of its samples. \pre none
  Image resolve() const;

 private:
  int width_, height_, ss_, sw_, sh_;
  std::vector<float> color_;  // sw×sh×3
  std::vector<double> depth_;
  long long written_ = 0;
};

/// A camera looking at the scene's bounding sphere from direction (azimuth, elevation), orthographic, Y up.
/// azimuth 0 / elevation 0 looks from +Z towards -Z ("front"); azimuth 90 from +X ("side"); elevation 90 from +Y
/// ("top").
struct ViewCamera {
  double azimuth_deg = 0;
  double elevation_deg = 0;
  double zoom = 1.0;  ///< 1: the bounding sphere fills the smaller image side with a 5% margin
};

/// "front", "side", "top" (also "back", "bottom", "iso" = azimuth 35, elevation 25).
/// \throw std::invalid_argument for any other name.
ViewCamera named_view(const std::string& name);

/// Projects world points to screen (x, y in output pixels, depth) for a camera framing the points `fit`.
class Projection {
 public:
  /// \pre width, height >= 1.
  Projection(const ViewCamera& camera, const Eigen::MatrixX3d& fit, int width, int height);
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const;
  /// Unit vector from the scene towards the viewer (for shading). \pre none
  const Eigen::Vector3d& toward_viewer() const { return back_; }
  /// Unit vector towards the key light: from the viewer's side, above and to the left. \pre none
  Eigen::Vector3d toward_light() const { return (back_ + 0.5 * up_ - 0.3 * right_).normalized(); }
  /// Output pixels per world unit. \pre none
  double scale() const { return scale_; }
  /// Depth range of the fitted scene (the bounding-sphere diameter). \pre none
  double depth_range() const { return 2 * radius_; }

 private:
  Eigen::Vector3d center_, right_, up_, back_;
  double scale_ = 1, radius_ = 1;
  double cx_ = 0, cy_ = 0;
};

}  // namespace quadcover
