// The pipeline's repairs of maps that no untangling can make injective (issue 14 item 3): the curve refinement
// (pipeline/curve_refinement.h) and the merging of coincident cones (pipeline/cone_merging.h), each compared with
// the same job without it on a shipped mesh where the cause occurs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "field/compute_frame_field.h"
#include "field/feature_alignment.h"
#include "field/relocation.h"
#include "mesh/vertex_rings.h"
#include "metrics/report.h"
#include "param/seams.h"
#include "pipeline/cone_merging.h"
#include "pipeline/curve_refinement.h"
#include "pipeline/job_report.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/validity_retries.h"
#include "support/angle_sums.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

/// Stuck faces (param/untangle.h) whose three corners lie on one integer iso-line of the map.
int faces_on_one_iso_line(const Parameterization& map) {
  int n = 0;
  for (int f : map.diagnostics.untangling.stuck_faces)
    for (int k = 0; k < 2; ++k) {
      bool on = true;
      const double line = k == 0 ? std::round(map.uv(f, 0).real()) : std::round(map.uv(f, 0).imag());
      for (int c = 0; c < 3; ++c) on = on && std::abs((k == 0 ? map.uv(f, c).real() : map.uv(f, c).imag()) - line) < 1e-9;
      if (on) {
        ++n;
        break;
      }
    }
  return n;
}

/// Stuck faces with two branch corners on one point.
int faces_with_coincident_cones(const Mesh& mesh, const Parameterization& map) {
  std::vector<char> branch(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const BranchPoint& b : map.branch_points) branch[b.vertex] = 1;
  int n = 0;
  for (int f : map.diagnostics.untangling.stuck_faces)
    for (int c = 0; c < 3; ++c)
      if (branch[mesh.F()(f, c)] && branch[mesh.F()(f, (c + 1) % 3)] &&
          std::abs(map.uv(f, c) - map.uv(f, (c + 1) % 3)) < 1e-9) {
        ++n;
        break;
      }
  return n;
}

TEST(CurveRefinement, NoTriangleKeepsThreeCurveCornersAndANonCurveEdge) {
  const Mesh mesh = testing::load_test_mesh("camelhead_boundary");
  const FeatureOptions features;
  const CurveRefinement r = refine_for_curves(mesh, features);
  ASSERT_TRUE(r.mesh);
  EXPECT_EQ(curve_refinement_edges(*r.mesh, features), std::vector<int>{}) << "one pass must be enough";
  EXPECT_EQ(r.mesh->num_faces(), mesh.num_faces() + r.added_faces);
  EXPECT_EQ(r.mesh->num_vertices(), mesh.num_vertices() + static_cast<int>(r.split.size()));
  EXPECT_EQ(r.mesh->genus(), mesh.genus());
  EXPECT_EQ(r.mesh->num_boundary_loops(), mesh.num_boundary_loops());
  EXPECT_NEAR(r.mesh->face_areas().sum(), mesh.face_areas().sum(), 1e-12 * mesh.face_areas().sum());
  // Nothing to do where no curve runs: a closed smooth surface.
  EXPECT_FALSE(refine_for_curves(testing::make_torus(48, 24), features).mesh);
}

TEST(CurveRefinement, RemovesTheFacesTheCurveConstraintsHoldOnOneIsoLine) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  // The fold refinement and the cone merges off: they remove these faces too (fold_refinement_test.cpp; merged
  // cones change the field there).
  // The curvature-guided field, whose map holds faces on one iso-line here.
  PipelineOptions plain;
  plain.field_style = FieldStyle::Curvature;
  plain.refine_curve_triangles = false;
  plain.fold_refinement_rounds = 0;
  plain.merge_coincident_cones = false;
  const ParamJob without = parameterize_mesh(mesh, plain);
  ASSERT_GT(faces_on_one_iso_line(without.map), 0) << "the case this test is about no longer occurs on bunny_3k";
  EXPECT_EQ(without.map.uv.rows(), mesh.num_faces());
  PipelineOptions refine;
  refine.field_style = FieldStyle::Curvature;
  refine.refine_curve_triangles = true;
  refine.fold_refinement_rounds = 0;
  refine.merge_coincident_cones = false;
  const ParamJob with = parameterize_mesh(mesh, refine);
  ASSERT_TRUE(with.refinement.mesh);
  EXPECT_EQ(&with.mesh(mesh), with.refinement.mesh.get());
  EXPECT_EQ(with.map.uv.rows(), with.mesh(mesh).num_faces());
  EXPECT_EQ(faces_on_one_iso_line(with.map), 0);
  EXPECT_FALSE(with.warnings.empty()) << "a refined triangulation is said";
}

TEST(ConeMerging, MergesCoincidentConesIntoOneAndLeavesFewerDegenerateTriangles) {
  const Mesh mesh = testing::load_test_mesh("cow");
  PipelineOptions plain;  // the fold refinement off: it would clean both maps
  plain.merge_coincident_cones = false;
  plain.separate_coincident_cones = false;  // the case before any re-rounding
  plain.fold_refinement_rounds = 0;
  const ParamJob without = parameterize_mesh(mesh, plain);
  const Mesh& m0 = without.mesh(mesh);
  ASSERT_GT(faces_with_coincident_cones(m0, without.map), 0) << "the case this test is about no longer occurs";
  const std::vector<ConeMerge> merges = coincident_cone_merges(m0, without.map);
  ASSERT_FALSE(merges.empty());
  for (const ConeMerge& c : merges) {
    EXPECT_GT(c.from, c.into);
    EXPECT_TRUE(c.quarters >= 1 && c.quarters <= 3);
  }
  PipelineOptions merge;
  merge.fold_refinement_rounds = 0;
  merge.separate_coincident_cones = false;
  const ParamJob with = parameterize_mesh(mesh, merge);
  EXPECT_GT(with.merged_cone_pairs, 0);
  EXPECT_LT(with.map.diagnostics.untangling.non_positive_after, without.map.diagnostics.untangling.non_positive_after);
  // Each merge turns at least one branch point into a regular vertex.
  EXPECT_LE(with.map.branch_points.size() + with.merged_cone_pairs, without.map.branch_points.size());
  // The index modulo 4 is moved, not lost: the sum over all branch points is the same modulo 4.
  auto sum_mod4 = [](const Parameterization& p) {
    int s = 0;
    for (const BranchPoint& b : p.branch_points) s += b.quarter_index;
    return ((s % 4) + 4) % 4;
  };
  EXPECT_EQ(sum_mod4(with.map), sum_mod4(without.map));
}

/// Per vertex of the map's mesh, its branch point's quarter index (0 elsewhere).
std::vector<int> target_quarters(const Mesh& mesh, const Parameterization& map) {
  std::vector<int> target(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (const BranchPoint& b : map.branch_points) target[b.vertex] = b.quarter_index;
  return target;
}

/// Triangles of the map with UV area ≤ 0, recounted from the corners.
int non_positive_triangles(const Parameterization& map) {
  int n = 0;
  for (int f = 0; f < map.uv.rows(); ++f) {
    const Complex e1 = map.uv(f, 1) - map.uv(f, 0), e2 = map.uv(f, 2) - map.uv(f, 0);
    n += std::imag(std::conj(e1) * e2) <= 0;
  }
  return n;
}

/// True iff vertices a and b share an edge.
bool adjacent(const Mesh& mesh, int a, int b) {
  for (const Mesh::FanCorner& c : mesh.fan(a))
    for (int k = 0; k < 3; ++k)
      if (mesh.F()(c.face, k) == b) return true;
  return false;
}

TEST(ConeMerging, MergesConesRoundedToOnePointTwoEdgesApart) {
  // camelhead: two +1 branch points two edges apart rounded to one lattice point; the one whose fan the map winds a
  // turn short keeps a flipped triangle that no untangling or refinement removes.
  const Mesh mesh = testing::load_test_mesh("camelhead_boundary");
  PipelineOptions plain;
  plain.merge_coincident_cones = false;
  plain.separate_coincident_cones = false;  // the case before any re-rounding
  plain.fold_refinement_rounds = 0;
  plain.validity_retries = 0;
  const ParamJob without = parameterize_mesh(mesh, plain);
  ASSERT_GT(without.map.diagnostics.untangling.non_positive_after, 0) << "the case this test is about no longer occurs";
  const std::vector<ConeMerge> merges = close_coincident_merges(mesh, without.map);
  const auto apart = std::count_if(merges.begin(), merges.end(), [&](const ConeMerge& m) {
    return !adjacent(mesh, m.from, m.into);
  });
  ASSERT_GT(apart, 0);
  auto on_lattice = [&](int v) {  // φ(v) in the chart of its first fan face
    const Mesh::FanCorner c = mesh.fan(v)[0];
    const Complex z = without.map.uv(c.face, c.corner);
    return std::abs(z - Complex(std::round(z.real()), std::round(z.imag()))) < 1e-9;
  };
  for (const ConeMerge& m : merges) {
    EXPECT_GT(m.from, m.into);
    EXPECT_TRUE(on_lattice(m.from) && on_lattice(m.into));
  }
  // With the merges (and everything else at its default) the map has no non-positive triangle: the job made it
  // again after the fold refinement had left the fold.
  const ParamJob with = parameterize_mesh(mesh, PipelineOptions{});
  EXPECT_GT(with.merged_cone_pairs, 0);
  EXPECT_TRUE(std::any_of(with.seconds.begin(), with.seconds.end(),
                          [](const auto& s) { return s.first == "close_cone_merging"; }));
  EXPECT_EQ(with.map.diagnostics.untangling.non_positive_after, 0);
  EXPECT_EQ(non_positive_triangles(with.map), 0);  // recounted from the written corners
}

/// Interior vertices whose winding, recounted from the corner angles, differs from their branch point's index.
int wrongly_wound(const Mesh& mesh, const Parameterization& map) {
  const Eigen::VectorXi wound = testing::quarter_index_by_angle_sums(mesh, map.uv);
  const std::vector<int> target = target_quarters(mesh, map);
  int n = 0;
  for (int v = 0; v < mesh.num_vertices(); ++v) n += !mesh.is_boundary_vertex(v) && wound[v] != target[v];
  return n;
}

/// The job without cone merges or validity retries (and without the cancelling of close opposite pairs before the
/// map, which removes some of the cases), with its map's windings and the field's targets.
struct WithoutMerges {
  ParamJob job;
  Eigen::VectorXi wound;
  std::vector<int> target;
};

WithoutMerges parameterize_without_merges(const Mesh& mesh, bool cancel_close_cones = false) {
  PipelineOptions plain;
  plain.cancel_close_cones = cancel_close_cones;
  plain.merge_coincident_cones = false;
  plain.separate_coincident_cones = false;  // the case before any re-rounding
  plain.validity_retries = 0;
  WithoutMerges w{parameterize_mesh(mesh, plain), {}, {}};
  const Mesh& m0 = w.job.mesh(mesh);
  w.wound = testing::quarter_index_by_angle_sums(m0, w.job.map.uv);
  w.target = target_quarters(m0, w.job.map);
  return w;
}

/// At the defaults (but for the cancelling of close opposite pairs) the job merges cones, and the written map winds as
/// the field everywhere, every triangle positive.
void expect_merged_and_valid_at_the_defaults(const Mesh& mesh) {
  SCOPED_TRACE("the default job");
  PipelineOptions o;
  o.cancel_close_cones = false;
  const ParamJob with = parameterize_mesh(mesh, o);
  EXPECT_GT(with.merged_cone_pairs, 0);
  EXPECT_EQ(wrongly_wound(with.mesh(mesh), with.map), 0);
  EXPECT_EQ(non_positive_triangles(with.map), 0);
}

TEST(ConeMerging, MergesOppositeConesOnOnePointWithARegularVertexWoundTwiceBetween) {
  // bunny_20k_holes: a +1/4 and a −1/4 branch point two edges apart rounded onto one lattice point. Both rings wind
  // as the field says; a regular vertex between them winds twice (4π), and no untangling undoes it.
  const Mesh mesh = testing::load_test_mesh("bunny_20k_holes");
  const WithoutMerges w = parameterize_without_merges(mesh);
  const Mesh& m0 = w.job.mesh(mesh);
  const Eigen::VectorXi& wound = w.wound;
  const std::vector<int>& target = w.target;
  const std::vector<ConeMerge> merges = close_coincident_merges(m0, w.job.map);
  const auto opposite_both_right = std::count_if(merges.begin(), merges.end(), [&](const ConeMerge& m) {
    return target[m.from] == -target[m.into] && wound[m.from] == target[m.from] && wound[m.into] == target[m.into];
  });
  ASSERT_GT(opposite_both_right, 0) << "the case this test is about no longer occurs";
  bool twice = false;  // the regular vertex between the pair
  for (int v = 0; v < m0.num_vertices(); ++v) twice = twice || (!m0.is_boundary_vertex(v) && target[v] == 0 && wound[v] == -4);
  EXPECT_TRUE(twice);
  for (const ConeMerge& m : merges) {
    EXPECT_GT(m.from, m.into);
    EXPECT_NE(target[m.from], 0);
    EXPECT_NE(target[m.into], 0);
  }
  expect_merged_and_valid_at_the_defaults(mesh);
  // Cancelled before the map (the default), no opposite pair is left on one point.
  const WithoutMerges c = parameterize_without_merges(mesh, true);
  EXPECT_GT(c.job.cancelled_close_pairs, 0);
  for (const ConeMerge& m : close_coincident_merges(c.job.mesh(mesh), c.job.map))
    EXPECT_NE(c.target[m.from], -c.target[m.into]) << m.from << " " << m.into;
}

TEST(ConeMerging, MergesConesOnOnePointSeveralRingsApartWhenOneIsWoundATurnOff) {
  // camelhead: two −1/4 branch points 7-8 rings apart rounded onto one lattice point; one winds π/2 instead of
  // 5π/2 with a regular vertex at 4π beside it. The near search (kNearRings) does not see the pair, the far one does.
  const Mesh mesh = testing::load_test_mesh("camelhead_boundary");
  const WithoutMerges w = parameterize_without_merges(mesh);
  const Mesh& m0 = w.job.mesh(mesh);
  const std::vector<ConeMerge> near = close_coincident_merges(m0, w.job.map, CoincidentReach::Near);
  const std::vector<ConeMerge> far = close_coincident_merges(m0, w.job.map, CoincidentReach::Far);
  int apart = 0;
  for (const ConeMerge& m : far) {
    const bool in_near =
        std::any_of(near.begin(), near.end(), [&](const ConeMerge& n) { return n.from == m.from && n.into == m.into; });
    if (in_near) continue;
    std::vector<char> seed(static_cast<std::size_t>(m0.num_vertices()), 0);
    seed[m.from] = 1;
    EXPECT_FALSE(grow_vertex_rings(m0, seed, kNearRings)[m.into]) << m.from << " " << m.into;
    EXPECT_TRUE(grow_vertex_rings(m0, seed, kFarRings)[m.into]) << m.from << " " << m.into;
    EXPECT_TRUE(w.wound[m.from] != w.target[m.from] || w.wound[m.into] != w.target[m.into]);
    ++apart;
  }
  ASSERT_GT(apart, 0) << "the case this test is about no longer occurs";
  expect_merged_and_valid_at_the_defaults(mesh);
}

/// The vertices sharing an edge with both a and b.
std::vector<int> common_neighbours(const Mesh& mesh, int a, int b) {
  std::vector<int> out;
  for (const Mesh::FanCorner& c : mesh.fan(a))
    for (int k = 1; k < 3; ++k) {
      const int n = mesh.F()(c.face, (c.corner + k) % 3);
      if (n != b && adjacent(mesh, n, b) && std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
    }
  return out;
}

TEST(ConeMerging, MergesConesOnOnePointWithACommonNeighbourBesideANonPositiveTriangle) {
  // mech_holes_shark at this h: two branch points with a common neighbour n rounded onto one lattice point. The edges
  // from n to both map onto one segment, so each of the two parts of n's fan between them turns by a multiple of 2π:
  // with n regular, one part has a triangle that is not positive whatever the untangling does, and no vertex beside
  // it winds wrong.
  const Mesh mesh = testing::load_test_mesh("mech_holes_shark");
  PipelineOptions plain;
  plain.param.density.edge_length = 0.02467533322728964;
  plain.merge_coincident_cones = false;
  plain.validity_retries = 0;
  const ParamJob without = parameterize_mesh(mesh, plain);
  const Mesh& m0 = without.mesh(mesh);
  ASSERT_GT(non_positive_triangles(without.map), 0) << "the case this test is about no longer occurs";
  ASSERT_EQ(wrongly_wound(m0, without.map), 0) << "the case this test is about no longer occurs";
  EXPECT_TRUE(close_coincident_merges(m0, without.map, CoincidentReach::Near).empty());  // no wrong winding near
  const std::vector<ConeMerge> merges =
      close_coincident_merges(m0, without.map, CoincidentReach::Near, CoincidentCause::AlsoFolds);
  ASSERT_FALSE(merges.empty());
  const bool shares_a_neighbour = std::any_of(merges.begin(), merges.end(), [&](const ConeMerge& m) {
    return !adjacent(m0, m.from, m.into) && !common_neighbours(m0, m.from, m.into).empty();
  });
  EXPECT_TRUE(shares_a_neighbour);
  PipelineOptions merging = plain;
  merging.merge_coincident_cones = true;
  const ParamJob with = parameterize_mesh(mesh, merging);
  EXPECT_GT(with.merged_cone_pairs, 0);
  EXPECT_EQ(non_positive_triangles(with.map), 0);  // recounted from the written corners
}

TEST(ConeSeparation, TheJobSetsApartTheConesItsRoundingPutOnOnePointWhenTheMapWindsWrongBesideThem) {
  // cow: two −1/4 branch points two edges apart rounded onto one lattice point; merging them leaves wrong windings.
  const Mesh mesh = testing::load_test_mesh("cow");
  // The field as a split of whole turns only leaves it (its two +3/4 cones kept): that field's rounding has the case.
  PipelineOptions whole_turns;
  whole_turns.split_min_quarters = 4;
  whole_turns.cancel_close_cones = false;  // it removes the pair
  PipelineOptions plain = whole_turns;
  plain.separate_coincident_cones = false;
  const ParamJob without = parameterize_mesh(mesh, plain);
  ASSERT_GT(wrongly_wound(without.mesh(mesh), without.map), 0) << "the case this test is about no longer occurs";
  EXPECT_FALSE(without.map.diagnostics.rounding.coincident_cones.empty());
  const ParamJob with = parameterize_mesh(mesh, whole_turns);
  EXPECT_EQ(wrongly_wound(with.mesh(mesh), with.map), 0);  // recounted from the corner angles
  EXPECT_EQ(non_positive_triangles(with.map), 0);
  EXPECT_FALSE(with.map.diagnostics.rounding.separated_cones.empty());
  EXPECT_TRUE(with.options.param.separate_close_cones);
  EXPECT_TRUE(std::any_of(with.seconds.begin(), with.seconds.end(),
                          [](const auto& s) { return s.first == "cone_separation"; }));
  EXPECT_FALSE(without.cone_separation.tried);
  EXPECT_TRUE(with.cone_separation.tried && with.cone_separation.kept);
  EXPECT_TRUE(with.cone_separation.validity.valid());
  // Every separated pair is a pair of the map's branch points.
  for (const auto& [p, q] : with.map.diagnostics.rounding.separated_cones) {
    const auto is_branch = [&](int v) {
      return std::any_of(with.map.branch_points.begin(), with.map.branch_points.end(),
                         [&](const BranchPoint& b) { return b.vertex == v; });
    };
    EXPECT_TRUE(is_branch(p) && is_branch(q)) << p << " " << q;
  }
}

TEST(RingRewinding, TheReportNamesTheConesWhoseDiskWasLaidOutAgain) {
  // fandisk: a branch point wound a turn short during the untangling whose disk (param/cone_disk_layout.h) is laid
  // out again; the final map winds there as the field says (the curvature-guided field's map).
  const Mesh mesh = testing::load_test_mesh("fandisk");
  PipelineOptions options;
  options.field_style = FieldStyle::Curvature;
  const ParamJob job = parameterize_mesh(mesh, options);
  const Mesh& m0 = job.mesh(mesh);
  const ParamDiagnostics::Untangling& u = job.map.diagnostics.untangling;
  ASSERT_FALSE(u.cone_disk_vertices.empty()) << "the case this test is about no longer occurs";
  const Eigen::VectorXi wound = testing::quarter_index_by_angle_sums(m0, job.map.uv);
  const std::vector<int> target = target_quarters(m0, job.map);
  for (const int v : u.cone_disk_vertices) {
    EXPECT_TRUE(std::binary_search(u.rewound_vertices.begin(), u.rewound_vertices.end(), v)) << v;
    EXPECT_NE(target[v], 0) << v;
    EXPECT_EQ(wound[v], target[v]) << v;
  }
  EXPECT_EQ(untangling_to_json(job.map)["cone_disk_vertices"].get<std::vector<int>>(), u.cone_disk_vertices);
}

TEST(RingRewinding, GivesUpTheCurveConstraintsBesideAConeRoundedOntoACurvesImage) {
  // fandisk: a −1/4 branch point two edges from a feature line is rounded onto that line's image; the strip
  // between them has no width, and the cone's ring winds a turn short with a regular vertex at 4π beside it (with
  // the long chains alone as features: crisp_crease_degrees = 0).
  const Mesh mesh = testing::load_test_mesh("fandisk");
  PipelineOptions chains_only;
  chains_only.param.features.crisp_crease_degrees = 0;
  PipelineOptions strict = chains_only;
  strict.param.untangle.release_near_wrong_windings = false;
  const ParamJob without = parameterize_mesh(mesh, strict);
  const Mesh& m0 = without.mesh(mesh);
  ASSERT_GT(wrongly_wound(m0, without.map), 0) << "the case this test is about no longer occurs";
  const ParamJob with = parameterize_mesh(mesh, chains_only);
  const Mesh& m1 = with.mesh(mesh);
  EXPECT_EQ(wrongly_wound(m1, with.map), 0);
  EXPECT_EQ(non_positive_triangles(with.map), 0);
  EXPECT_TRUE(measure_seams(m1, with.map.uv, 1e-9).seamless);
  // The constraints given up: curve vertices of the input within 3 rings of the wrongly wound ones (2 rings of
  // the refined mesh's), listed, and the curves report that they left their lines.
  std::vector<char> wrong_input(static_cast<std::size_t>(mesh.num_vertices()), 0);
  for (int v : wrong_winding_vertices(m0, without.map))
    if (v < mesh.num_vertices()) wrong_input[v] = 1;
  const std::vector<char> near = grow_vertex_rings(mesh, std::move(wrong_input), 3);
  const auto& before = without.map.diagnostics.untangling.released_vertices;
  int newly = 0;
  for (int v : with.map.diagnostics.untangling.released_vertices) {
    if (std::find(before.begin(), before.end(), v) != before.end() || v >= mesh.num_vertices()) continue;
    ++newly;
    EXPECT_TRUE(near[v]) << v;
  }
  EXPECT_GT(newly, 0);
  double deviation = 0;
  for (const Parameterization::Curve& c : with.map.aligned_curves) deviation = std::max(deviation, c.max_deviation);
  EXPECT_GT(deviation, 1e-6);
}

TEST(ConeMoves, FakeConePairsMoveToTheVertexTheMapWindsAroundAndFewerStayWrong) {
  const Mesh mesh = testing::load_test_mesh("couplingdown_genus9");
  PipelineOptions plain;  // one density for both jobs, the moves alone (no merges of coincident cones)
  plain.field_style = FieldStyle::Curvature;  // the field whose map has the fake pairs
  plain.validity_retries = 0;
  plain.move_wound_cones = false;
  plain.merge_coincident_cones = false;
  plain.square_hole_grid_units = 0;  // the field of the map with the fake pairs: every rim followed on both sides
  const ParamJob without = parameterize_mesh(mesh, plain);
  const Mesh& m0 = without.mesh(mesh);
  const std::size_t wrong_before = wrong_winding_vertices(m0, without.map).size();
  ASSERT_GT(wrong_before, 0u) << "the case this test is about no longer occurs";
  // Every move pairs a branch point wound one turn off with a regular interior vertex wound the opposite turn,
  // recomputed from the corner angles.
  const Eigen::VectorXi wound = testing::quarter_index_by_angle_sums(m0, without.map.uv);
  std::vector<int> target(static_cast<std::size_t>(m0.num_vertices()), 0);
  for (const BranchPoint& b : without.map.branch_points) target[b.vertex] = b.quarter_index;
  const std::vector<ConeMerge> moves = wound_cone_moves(m0, without.map);
  ASSERT_FALSE(moves.empty());
  for (const ConeMerge& m : moves) {
    EXPECT_NE(target[m.from], 0);
    EXPECT_EQ(target[m.into], 0);
    EXPECT_EQ(std::abs(wound[m.from] - target[m.from]), 4);
    EXPECT_EQ(wound[m.into] - target[m.into], -(wound[m.from] - target[m.from]));
    EXPECT_EQ(m.quarters, ((target[m.from] % 4) + 4) % 4);
  }
  PipelineOptions move = plain;
  move.move_wound_cones = true;
  const ParamJob with = parameterize_mesh(mesh, move);
  EXPECT_GT(with.moved_wound_cones, 0);
  EXPECT_LT(wrong_winding_vertices(with.mesh(mesh), with.map).size(), wrong_before);
  EXPECT_LE(with.map.diagnostics.untangling.non_positive_after, without.map.diagnostics.untangling.non_positive_after);
}

TEST(FeatureCounts, TheReportCountsTheInputsSharpEdgesNotTheRefinedHalves) {
  const Mesh mesh = testing::load_test_mesh("fandisk");
  PipelineOptions chains_only;  // the long chains alone as features: this map is refined
  chains_only.param.features.crisp_crease_degrees = 0;
  const ParamJob job = parameterize_mesh(mesh, chains_only);
  ASSERT_GT(job.refinement.split.size(), 0u) << "the case this test is about (a refined map) no longer occurs";
  const nlohmann::json r = param_report(mesh, job, job.map.uv, "fandisk");
  const FeatureConstraints input = feature_constraints(mesh, field_stage_options(job.options).features);
  EXPECT_EQ(r["field"]["features"]["sharp_edges"].get<std::size_t>(), input.feature_edges.size());
  EXPECT_EQ(r["field"]["features"]["constrained_faces"].get<long>(),
            std::count(input.constrained.begin(), input.constrained.end(), 1));
}

TEST(CloseOppositeCones, PairsTheNearestOppositeConesCloserThanTheDistanceEachVertexOnce) {
  const Mesh grid = testing::make_grid(10);  // spacing 0.1
  const auto id = [](int i, int j) { return j * 11 + i; };
  // a +1 with a −1 beside it (0.1) and another −1 two steps below (0.2); two −1/+1 two steps apart (0.2); two +1
  // side by side (same sign: never a pair).
  const int a = id(3, 5), b = id(4, 5), below = id(3, 3), c = id(6, 5), d = id(8, 5), e = id(2, 7), g = id(2, 8);
  std::vector<BranchPoint> points{{below, -1}, {a, 1}, {b, -1}, {c, -1}, {d, 1}, {e, 1}, {g, 1}};
  std::sort(points.begin(), points.end(),
            [](const BranchPoint& x, const BranchPoint& y) { return x.vertex < y.vertex; });
  const auto merges = close_opposite_cone_merges(grid, points, 0.25);
  ASSERT_EQ(merges.size(), 2u);
  // a goes with its nearest partner b, not with `below`; c with d; from the higher vertex number; the quarters of
  // `from` modulo 4.
  EXPECT_EQ(merges[0].from, b);
  EXPECT_EQ(merges[0].into, a);
  EXPECT_EQ(merges[0].quarters, 3);
  EXPECT_EQ(merges[1].from, d);
  EXPECT_EQ(merges[1].into, c);
  EXPECT_EQ(merges[1].quarters, 1);
  // Closer than 0.15: only the pair 0.1 apart; with nothing closer than 0.05, none.
  const auto near = close_opposite_cone_merges(grid, points, 0.15);
  ASSERT_EQ(near.size(), 1u);
  EXPECT_EQ(near[0].into, a);
  EXPECT_TRUE(close_opposite_cone_merges(grid, points, 0.05).empty());
}

TEST(CloseOppositeCones, OnAComponentMeshedFinerTheDistanceIsItsShorterQuadEdge) {
  // Two copies of one grid (spacing 0.1), each with a +1/−1 pair 0.2 apart: within 0.25 on the first (ρ = 1), not
  // on the second when it is meshed twice as finely (quad edge 0.125), again when both are at ρ = 1.
  const Mesh grid = testing::make_grid(10);
  const int n = static_cast<int>(grid.num_vertices());
  Eigen::MatrixX3d V(2 * n, 3);
  V << grid.V(), grid.V().rowwise() + Eigen::RowVector3d(2, 0, 0);
  Eigen::MatrixX3i F(2 * grid.num_faces(), 3);
  F << grid.F(), grid.F().array() + n;
  const Mesh two = Mesh::from_triangles(V, F);
  ASSERT_EQ(two.num_components(), 2);
  const int a = 5 * 11 + 3, b = 5 * 11 + 5;  // (3, 5) and (5, 5)
  const std::vector<BranchPoint> points{{a, 1}, {b, -1}, {n + a, 1}, {n + b, -1}};
  const auto finer = close_opposite_cone_merges(two, points, 0.25, {1.0, 2.0});
  ASSERT_EQ(finer.size(), 1u);
  EXPECT_EQ(finer[0].into, a);
  EXPECT_EQ(close_opposite_cone_merges(two, points, 0.25, {1.0, 1.0}).size(), 2u);
  EXPECT_EQ(close_opposite_cone_merges(two, points, 0.25).size(), 2u);
}

TEST(CloseOppositeCones, MeasuresAlongInteriorEdgesSoThatEveryPairHasAPathToMergeAlong) {
  // Two 4 × 4 grids (spacing 0.25) joined by one strip quad between boundary vertices: the interior vertices 13 (left)
  // and 36 (right) are 0.75 apart through the strip, but every path between them through interior edges passes a
  // boundary vertex, so relocation_path has none.
  const Mesh grid = testing::make_grid(4);
  Eigen::MatrixX3d V(50, 3);
  V << grid.V(), grid.V().rowwise() + Eigen::RowVector3d(1.25, 0, 0);
  Eigen::MatrixX3i F(grid.num_faces() * 2 + 2, 3);
  F << grid.F(), grid.F().array() + 25, Eigen::RowVector3i(14, 35, 40), Eigen::RowVector3i(14, 40, 19);
  const Mesh joined = Mesh::from_triangles(V, F);
  ASSERT_TRUE(joined.is_boundary_vertex(14) && !joined.is_boundary_vertex(13) && !joined.is_boundary_vertex(36));
  EXPECT_THROW(relocation_path(joined, 13, 36), std::invalid_argument);
  EXPECT_TRUE(close_opposite_cone_merges(joined, {{13, 1}, {36, -1}}, 1.0).empty());
  const auto inside = close_opposite_cone_merges(joined, {{11, -1}, {13, 1}}, 1.0);  // 0.5 apart on the left grid
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_EQ(relocation_path(joined, inside[0].from, inside[0].into).size(), 3u);
}

TEST(CloseOppositeCones, TheJobCancelsThemBeforeTheMapAndReportsHowMany) {
  // cow's field has opposite branch points less than one quad edge apart. With the optimization and every later
  // cone change off, the map's cones are the field's less the cancelled pairs.
  const Mesh mesh = testing::load_test_mesh("cow");
  PipelineOptions o;
  o.optimize = OptimizeMode::None;
  o.merge_coincident_cones = o.move_wound_cones = o.separate_coincident_cones = false;
  o.fold_refinement_rounds = o.validity_retries = 0;
  const ParamJob on = parameterize_mesh(mesh, o);
  const FrameFieldResult field = compute_frame_field_detailed(mesh, field_stage_options(on.options));  // resolved
  const double h = on.map.edge_length;
  const std::size_t close = close_opposite_cone_merges(mesh, field.branch_points, h).size();
  ASSERT_GT(close, 0u) << "the case this test is about no longer occurs on cow";
  EXPECT_EQ(on.cancelled_close_pairs, static_cast<int>(close));
  EXPECT_EQ(on.map.branch_points.size(), field.branch_points.size() - 2 * close);
  EXPECT_TRUE(close_opposite_cone_merges(mesh, on.map.branch_points, h).empty());
  const nlohmann::json report = param_report(mesh, on, on.map.uv);
  EXPECT_EQ(report["field"]["cancelled_close_pairs"]["original"], close);
  EXPECT_EQ(report["field"]["cancelled_close_pairs"]["optimized"], 0);
  o.cancel_close_cones = false;
  const ParamJob off = parameterize_mesh(mesh, o);
  EXPECT_EQ(off.cancelled_close_pairs, 0);
  EXPECT_EQ(off.map.branch_points.size(), field.branch_points.size());
}

}  // namespace
}  // namespace quadcover
