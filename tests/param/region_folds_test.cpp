// RegionFolds (param/region_folds.h) against the whole-map count it replaces in the untangling: flipped_triangles of
// base − layered_values(u) over the faces not held stuck, for maps moved inside a region only (small and large
// moves, triangles near the collapse threshold outside the region, a threshold pushed out of its band).
#include "param/region_folds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "field/compute_frame_field.h"
#include "param/parameterize.h"
#include "param/seams.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

struct RegionSetup {
  Mesh mesh;
  VertexLayers layers;
  Eigen::MatrixX3cd base;
  std::vector<char> stuck, region_fixed;
};

// bunny_3k's map as the base; every 17th face stuck; the region is the vertices of the first 300 faces; two faces
// outside it shrunk to just below and just above the collapse threshold of the unmoved map.
RegionSetup make_setup() {
  RegionSetup s{testing::load_test_mesh("bunny_3k"), {}, {}, {}, {}};
  const Mesh& mesh = s.mesh;
  const FrameField field = compute_frame_field(mesh);
  s.layers = vertex_layers(mesh, field.matching);
  s.base = parameterize(mesh, field).uv;
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  s.stuck.assign(nf, 0);
  for (int f = 0; f < nf; f += 17) s.stuck[f] = 1;
  s.region_fixed.assign(2 * nv, 1);
  for (int f = 0; f < 300; ++f)
    for (int c = 0; c < 3; ++c) s.region_fixed[mesh.F()(f, c)] = s.region_fixed[nv + mesh.F()(f, c)] = 0;
  const double ratio = [&] {
    double uv = 0;
    for (int f = 0; f < nf; ++f) uv += std::abs(signed_uv_area(s.base, f));
    return uv / mesh.face_areas().sum();
  }();
  for (const auto& [f, factor] : {std::pair{nf - 2, 0.999}, std::pair{nf - 5, 1.001}}) {
    const double target = factor * flip_tolerance * mesh.face_areas()[f] * ratio;
    const Complex centre = (s.base(f, 0) + s.base(f, 1) + s.base(f, 2)) / 3.0;
    const double shrink = std::sqrt(target / signed_uv_area(s.base, f));
    for (int c = 0; c < 3; ++c) s.base(f, c) = centre + shrink * (s.base(f, c) - centre);
  }
  // Both sit at the threshold: the one below counts, the one above not (the two shrinks barely move Σ|A_uv|).
  const std::vector<int> non_positive = flipped_triangles(mesh, s.base).flipped_faces;
  EXPECT_TRUE(std::binary_search(non_positive.begin(), non_positive.end(), nf - 2));
  EXPECT_FALSE(std::binary_search(non_positive.begin(), non_positive.end(), nf - 5));
  return s;
}

int whole_map_count(const RegionSetup& s, const Eigen::VectorXd& Y) {
  const Eigen::Index nv = Y.size() / 2;
  Eigen::VectorXcd u(nv);
  for (Eigen::Index p = 0; p < nv; ++p) u[p] = Complex(Y[p], Y[nv + p]);
  int count = 0;
  for (int f : flipped_triangles(s.mesh, Eigen::MatrixX3cd(s.base - layered_values(s.mesh, s.layers, u))).flipped_faces)
    count += !s.stuck[f];
  return count;
}

TEST(RegionFolds, CountsAsTheWholeMapForMovesInsideTheRegion) {
  const RegionSetup s = make_setup();
  const int nv = s.mesh.num_vertices();
  const Eigen::VectorXd X = Eigen::VectorXd::Zero(2 * nv);
  const RegionFolds folds(s.mesh, s.layers, s.base, s.stuck, s.region_fixed, X);
  EXPECT_EQ(folds(X), whole_map_count(s, X));
  std::mt19937 rng(7);
  std::normal_distribution<double> g(0, 1);
  int folded = 0;
  // Small moves fold a few triangles and shift Σ|A_uv| a little; large ones move the threshold out of its band.
  for (const double scale : {1e-4, 1e-2, 0.3, 3.0, 300.0}) {
    for (int trial = 0; trial < 4; ++trial) {
      Eigen::VectorXd Y = X;
      for (int i = 0; i < 2 * nv; ++i)
        if (!s.region_fixed[i]) Y[i] = scale * g(rng);
      const int expected = whole_map_count(s, Y);
      EXPECT_EQ(folds(Y), expected) << "scale " << scale;
      folded = std::max(folded, expected);
    }
  }
  EXPECT_GT(folded, 50);  // the moves did fold triangles: the comparison is not between zeros
}

}  // namespace
}  // namespace quadcover
