// Seamlessness and flips measured from per-corner coordinates.
#include "param/seams.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace quadcover {

namespace {
Complex round_gauss(Complex z) { return {std::round(z.real()), std::round(z.imag())}; }
}  // namespace

SeamReport measure_seams(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double relative_tolerance) {
  SeamReport r;
  double minx = INFINITY, maxx = -INFINITY, miny = INFINITY, maxy = -INFINITY;
  for (Eigen::Index i = 0; i < uv.size(); ++i) {
    minx = std::min(minx, uv(i).real()), maxx = std::max(maxx, uv(i).real());
    miny = std::min(miny, uv(i).imag()), maxy = std::max(maxy, uv(i).imag());
  }
  r.parameter_extent = uv.size() ? std::hypot(maxx - minx, maxy - miny) : 0;
  const double tol = relative_tolerance * std::max(r.parameter_extent, 1.0);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int s = mesh.EF()(e, 0), t = mesh.EF()(e, 1);
    if (s < 0 || t < 0) continue;
    const int a = mesh.E()(e, 0), b = mesh.E()(e, 1);
    const Complex sa = uv(s, mesh.corner_of(s, a)), sb = uv(s, mesh.corner_of(s, b));
    const Complex ta = uv(t, mesh.corner_of(t, a)), tb = uv(t, mesh.corner_of(t, b));
    double best = INFINITY;
    bool identity = false;
    for (int k = 0; k < 4; ++k) {
      const Complex ca = ta - ipow(k) * sa, cb = tb - ipow(k) * sb;
      const Complex c = round_gauss(0.5 * (ca + cb));
      const double err = std::max(std::abs(ca - c), std::abs(cb - c));
      if (err < best) {
        best = err;
        identity = k == 0 && c == Complex(0);
      }
    }
    if (!identity) ++r.cut_edges;
    r.max_transition_error = std::max(r.max_transition_error, best);
    if (best > tol) r.bad_edges.push_back(e);
  }
  r.seamless = r.bad_edges.empty();
  return r;
}

FlipReport flipped_triangles(const Mesh& mesh, const Eigen::MatrixX3cd& uv, double tolerance) {
  return flipped_triangles(mesh.face_areas(), uv, tolerance);
}

FlipReport flipped_triangles(const Eigen::VectorXd& face_areas, const Eigen::MatrixX3cd& uv, double tolerance) {
  FlipReport r;
  const Eigen::Index nf = uv.rows();
  std::vector<double> area(static_cast<std::size_t>(nf));
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, nf, 4096), [&](const tbb::blocked_range<Eigen::Index>& faces) {
    for (Eigen::Index f = faces.begin(); f < faces.end(); ++f) area[f] = signed_uv_area(uv, f);
  });
  double total_uv = 0;  // summed in face order: the same total for every thread count
  for (Eigen::Index f = 0; f < nf; ++f) {
    total_uv += std::abs(area[f]);
    r.parameter_area += area[f];
  }
  const double total_3d = face_areas.sum();
  const double ratio = total_3d > 0 ? total_uv / total_3d : 0;
  for (Eigen::Index f = 0; f < nf; ++f) {
    const double ref = tolerance * face_areas[f] * ratio;
    if (!non_positive_uv_area(area[f], ref)) continue;
    ++(collapsed_uv_area(area[f], ref) ? r.collapsed : r.flipped);
    r.flipped_faces.push_back(static_cast<int>(f));
  }
  r.non_positive = r.flipped + r.collapsed;
  return r;
}

}  // namespace quadcover
