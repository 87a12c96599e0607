// Branch points kept off one lattice point by re-rounded periods (param/cone_separation.h): each branch point's image
// is the fixed point of its composed transitions, the pair offsets agree with the map developed around a cone, and
// the separated rounding leaves no close pair on one point, moving the periods by lattice steps only.
#include "param/cone_separation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "field/compute_frame_field.h"
#include "param/map_development.h"
#include "param/parameterize.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// cow's field with whole turns split only (its two +3/4 cones kept), whose rounding puts close cones on one point.
FieldOptions whole_turns_split() {
  FieldOptions o;
  o.split_min_quarters = 4;
  return o;
}

struct SolvedCow {
  Mesh mesh = testing::load_test_mesh("cow");
  FrameField field = compute_frame_field(mesh, whole_turns_split());
  CoverCut cut = build_cover_cut(mesh, field.matching);

  Parameterization map(bool separate) const {
    ParamOptions options;
    options.separate_close_cones = separate;
    return parameterize(mesh, field, options);
  }
};

const SolvedCow& cow() {
  static const SolvedCow solved;
  return solved;
}

/// The corner value of vertex v in face f.
Complex corner_value(const Mesh& mesh, const Eigen::MatrixX3cd& uv, int f, int v) {
  for (int c = 0; c < 3; ++c)
    if (mesh.F()(f, c) == v) return uv(f, c);
  ADD_FAILURE() << "vertex " << v << " not in face " << f;
  return 0;
}

/// The offsets of q's copies from p in the map developed over the faces around p (param/map_development.h).
std::vector<Complex> developed_offsets(const Mesh& mesh, const Parameterization& map, ConePair pair) {
  const VertexLayers layers{map.subspace.layer, map.subspace.branch};
  const Eigen::VectorXcd zero = Eigen::VectorXcd::Zero(mesh.num_vertices());
  const auto around = developed_around(mesh, layers, map.uv, zero, pair.p, 1);
  Complex at = 0;
  for (const auto& [v, z] : around)
    if (v == pair.p) at = z;
  std::vector<Complex> out;
  for (const auto& [v, z] : around)
    if (v == pair.q) out.push_back(z - at);
  return out;
}

TEST(ConeSeparation, EveryBranchPointSitsOnTheFixedPointOfItsTransitions) {
  const SolvedCow& s = cow();
  const Parameterization map = s.map(true);
  int checked = 0;
  for (const BranchPoint& b : map.branch_points) {
    const int v = b.vertex;
    if (s.mesh.is_boundary_vertex(v)) continue;
    const int f = fan_crossings(s.mesh, v).front().from;
    EXPECT_LT(
        std::abs(branch_point_image(s.mesh, s.cut, map.transition_translation, v) - corner_value(s.mesh, map.uv, f, v)),
        1e-6)
        << v;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(ConeSeparation, PairOffsetsAreTheMapsOwnOffsetsAndCountTheCoincidentPairs) {
  const SolvedCow& s = cow();
  std::vector<std::pair<int, int>> listed;  // by the rounding without separation
  for (const bool separate : {false, true}) {
    const Parameterization map = s.map(separate);
    const std::vector<ConePair> pairs = close_branch_points(s.mesh, s.cut, kWatchedRings);
    ASSERT_GT(pairs.size(), 20u);
    std::vector<std::pair<int, int>> on_one_point;
    int adjacent = 0;
    for (const ConePair& pair : pairs) {
      const Complex offset = ConePairOffset(s.mesh, s.cut, pair)(map.transition_translation);
      EXPECT_LT(distance_to_gaussian_integers(2.0 * offset), 1e-6) << "branch points sit on lattice or cell centres";
      if (std::abs(offset) < 0.25) on_one_point.emplace_back(pair.p, pair.q);
      // Across one edge the paths around p or q differ by their own turns only: the same distance.
      for (const Complex& z : developed_offsets(s.mesh, map, pair)) {
        EXPECT_NEAR(std::abs(z), std::abs(offset), 1e-6) << pair.p << " " << pair.q;
        ++adjacent;
      }
    }
    EXPECT_GT(adjacent, 0);
    const auto& r = map.diagnostics.rounding;
    EXPECT_EQ(static_cast<int>(on_one_point.size()), r.coincident_cone_pairs_left);
    if (!separate) {
      EXPECT_FALSE(on_one_point.empty()) << "the cow's rounding puts close cones on one point: the case under test";
      EXPECT_EQ(on_one_point, r.coincident_cones);  // recounted from the map's own transitions
      EXPECT_TRUE(r.separated_cones.empty());
      listed = r.coincident_cones;
    } else {
      EXPECT_EQ(r.coincident_cones, listed);  // the same rounding before the steps
      EXPECT_TRUE(on_one_point.empty());
      EXPECT_EQ(r.separated_cones, listed);
    }
  }
}

TEST(ConeSeparation, TheSeparatedPeriodsDifferByLatticeSteps) {
  const SolvedCow& s = cow();
  const Parameterization plain = s.map(false), separated = s.map(true);
  ASSERT_EQ(plain.rounded_periods.size(), separated.rounded_periods.size());
  int changed = 0;
  for (std::size_t j = 0; j < plain.rounded_periods.size(); ++j) {
    const Complex step = separated.rounded_periods[j] - plain.rounded_periods[j];
    EXPECT_LT(std::abs(step - round_to_lattice(step, Lattice::Rotated)), 1e-9) << j;
    changed += std::abs(step) > 0.5;
  }
  EXPECT_GT(changed, 0);
  EXPECT_LE(changed, static_cast<int>(separated.diagnostics.rounding.coincident_cones.size()));  // a pair per step
}

}  // namespace
}  // namespace quadcover
