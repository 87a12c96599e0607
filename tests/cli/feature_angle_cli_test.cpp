// `param` / `remesh --feature-angle DEG|off --align BOOL --round-curves BOOL` through the real binary: the angle
// reaches the field stage (report field.features: constrained faces and sharp edges follow it), 'off' keeps the
// boundaries, the options section names it, an angle outside [0, 180] is refused (exit 2) before anything is
// written, and --round-curves puts lilium_disk's boundary loop on quad edges. `--features FILE` gives the sharp edges
// instead (a bad file is refused naming its line), `--no-features` turns them off in the field and the smoothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "field/feature_alignment.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using quadcover::testing::run_cli;

class FeatureAngleCli : public quadcover::testing::FolderTest {
 protected:
  FeatureAngleCli() : FolderTest("feature_angle_cli") {}

  /// Runs `COMMAND MESH --feature-angle ANGLE EXTRA` without the repairs (kWithoutRepairs: the feature curves are
  /// decided before them) and returns its report.
  nlohmann::json report(const std::string& command, const std::string& mesh, const std::string& angle,
                        const std::string& extra = "") {
    return quadcover::testing::run_cli_report(
        command + " " + quadcover::testing::data_path(mesh) + " -o " + path("out.obj") +
            quadcover::testing::kWithoutRepairs + " -q" + (angle.empty() ? "" : " --feature-angle " + angle) +
            " " + extra,
        path(command + "_" + mesh + "_" + angle + ".json"));
  }
};

TEST_F(FeatureAngleCli, AngleReachesTheFieldStageAndTheReport) {
  const nlohmann::json by_default = report("param", "fandisk", "");
  const nlohmann::json at35 = report("param", "fandisk", "35");
  const nlohmann::json at80 = report("param", "fandisk", "80");
  const nlohmann::json off = report("param", "fandisk", "off");
  EXPECT_EQ(by_default["options"]["feature_angle"], 35.0);
  EXPECT_EQ(at80["options"]["feature_angle"], 80.0);
  EXPECT_EQ(off["options"]["feature_angle"], 0.0);
  EXPECT_EQ(by_default["field"]["features"], at35["field"]["features"]);
  const auto sharp = [](const nlohmann::json& r) { return r["field"]["features"]["sharp_edges"].get<int>(); };
  const auto fixed = [](const nlohmann::json& r) { return r["field"]["features"]["constrained_faces"].get<int>(); };
  // fandisk is closed: without sharp features no face is constrained and no curve is aligned.
  EXPECT_GT(sharp(at35), 100);
  EXPECT_GT(fixed(at35), sharp(at35));  // each sharp edge fixes its faces, the two faces of an edge are distinct
  EXPECT_EQ(sharp(off), 0);
  EXPECT_EQ(fixed(off), 0);
  EXPECT_TRUE(off["aligned_curves"]["curves"].empty());
  EXPECT_FALSE(at35["aligned_curves"]["curves"].empty());
  // A larger angle keeps a subset of the sharp edges.
  EXPECT_LT(sharp(at80), sharp(at35));
  EXPECT_GT(sharp(at80), 0);
  // Another field stage: different crosses on the same mesh at another angle (the field follows the angle).
  EXPECT_NE(at35["parameterization"]["energy_curl"], off["parameterization"]["energy_curl"]);
}

TEST_F(FeatureAngleCli, OffKeepsTheBoundariesAligned) {
  const nlohmann::json off = report("remesh", "camelhead_boundary", "off");
  EXPECT_EQ(off["field"]["features"]["sharp_edges"], 0);
  EXPECT_TRUE(off["field"]["features"]["boundaries"].get<bool>());
  EXPECT_GT(off["field"]["features"]["constrained_faces"].get<int>(), 0);
  EXPECT_FALSE(off["aligned_curves"]["curves"].empty());  // the boundary loop still lies on an iso-line
  const nlohmann::json free = report("remesh", "camelhead_boundary", "off", "--align false");
  EXPECT_FALSE(free["options"]["align_curves"].get<bool>());
  EXPECT_TRUE(free["aligned_curves"]["curves"].empty());
}

// `remesh --round-curves true` on lilium_disk: the boundary loop is one integer iso-line (its line enforced, the
// rounding reports the line it rounded), so the quad mesh is all quads up to the boundary; without it the loop is left
// free (with its reason) and the boundary cells are clipped polygons (--boundary-quads false keeps them; by default
// they are made quads, with the same loop left free).
TEST_F(FeatureAngleCli, RoundCurvesPutsTheBoundaryLoopOnQuadEdges) {
  const nlohmann::json plain = report("remesh", "lilium_disk", "", "--boundary-quads false");
  const nlohmann::json rounded = report("remesh", "lilium_disk", "", "--round-curves true --boundary-quads false");
  const nlohmann::json made = report("remesh", "lilium_disk", "");
  EXPECT_FALSE(plain["options"]["boundary_quads"].get<bool>());
  EXPECT_TRUE(made["options"]["boundary_quads"].get<bool>());
  EXPECT_EQ(made["quad_mesh"]["non_quads"], 0);
  EXPECT_GT(made["extraction"]["boundary_collapsed_triangles"].get<int>() +
                made["extraction"]["boundary_split_polygons"].get<int>(),
            0);
  EXPECT_EQ(made["aligned_curves"]["curves"][0]["left_free_because"], "closes on itself with another integer");
  EXPECT_TRUE(made["surface_check"]["same_topology"].get<bool>());
  EXPECT_FALSE(plain["options"]["round_curves"].get<bool>());
  EXPECT_TRUE(rounded["options"]["round_curves"].get<bool>());
  EXPECT_EQ(plain["rounding"]["curve_lines"], 0);
  EXPECT_EQ(rounded["rounding"]["curve_lines"], 1);
  EXPECT_FALSE(rounded["rounding"]["curve_rounding_dropped"].get<bool>());
  ASSERT_EQ(rounded["aligned_curves"]["curves"].size(), 1u);
  EXPECT_TRUE(rounded["aligned_curves"]["curves"][0]["enforced"].get<bool>());
  EXPECT_TRUE(rounded["aligned_curves"]["curves"][0]["left_free_because"].is_null());
  EXPECT_FALSE(plain["aligned_curves"]["curves"][0]["enforced"].get<bool>());
  EXPECT_EQ(plain["aligned_curves"]["curves"][0]["left_free_because"], "closes on itself with another integer");
  EXPECT_GT(plain["quad_mesh"]["non_quads"].get<int>(), 0);
  EXPECT_EQ(rounded["quad_mesh"]["non_quads"], 0);
  EXPECT_EQ(rounded["quad_mesh"]["boundary_loops"], 1);
}

// The given edges are the sharp features, whatever their angle: fandisk's edges above 35° (min_curve_edges 1: more
// than the detection keeps) plus one flat edge are all followed, and no other edge is.
TEST_F(FeatureAngleCli, GivenFeaturesReplaceTheDetection) {
  const quadcover::Mesh mesh = quadcover::testing::load_test_mesh("fandisk");  // no unreferenced vertex
  quadcover::FeatureOptions every;
  every.min_curve_edges = 1;
  std::vector<int> edges = quadcover::feature_constraints(mesh, every).feature_edges;
  const auto detected = quadcover::feature_constraints(mesh).feature_edges.size();
  ASSERT_GT(edges.size(), detected);
  int flat = 0;
  while (flat < mesh.num_edges() &&
         (std::find(edges.begin(), edges.end(), flat) != edges.end() || mesh.is_boundary_edge(flat)))
    ++flat;
  edges.push_back(flat);
  {
    std::ofstream file(path("given.txt"));
    file << "# fandisk: the edges above 35 degrees and one flat edge\n\n";
    for (int e : edges) file << mesh.E()(e, 0) + 1 << " " << mesh.E()(e, 1) + 1 << "  # edge " << e << "\n";
  }
  const nlohmann::json given = report("param", "fandisk", "", "--features " + path("given.txt"));
  EXPECT_EQ(given["field"]["features"]["given_edges"], edges.size());
  EXPECT_EQ(given["field"]["features"]["sharp_edges"], edges.size());
  EXPECT_TRUE(given["field"]["features"]["sharp_angle_degrees"].is_null());
  EXPECT_TRUE(given["options"]["feature_angle"].is_null());
  EXPECT_EQ(given["options"]["given_feature_edges"], edges.size());
  EXPECT_GT(given["field"]["features"]["constrained_faces"].get<int>(),
            report("param", "fandisk", "")["field"]["features"]["constrained_faces"].get<int>());
}

// `field --save-features F` writes the edges the field followed; `remesh --features F` then makes the same quads as
// the detection, byte for byte. Two inputs with --save-features are refused.
TEST_F(FeatureAngleCli, SavedFeaturesGiveBackTheSameQuads) {
  const std::string mesh = quadcover::testing::data_path("fandisk");
  ASSERT_EQ(run_cli("field " + mesh + " -o " + path("f.json") + " -q --save-features " + path("saved.txt")).code, 0);
  const std::string saved = quadcover::testing::slurp(path("saved.txt"));
  EXPECT_EQ(saved.rfind("# quadcover: the 682 sharp edges the field followed (dihedral angle above 35 degrees", 0), 0u)
      << saved.substr(0, 200);
  // The same command again replaces its own output (the saved file is not an input of it).
  const auto again = run_cli("field " + mesh + " -o " + path("f.json") + " -q --save-features " + path("saved.txt"));
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(quadcover::testing::slurp(path("saved.txt")), saved);
  const std::string common = std::string(quadcover::testing::kWithoutRepairs) + " -q";
  ASSERT_EQ(run_cli("remesh " + mesh + " -o " + path("given.obj") + common + " --features " + path("saved.txt")).code,
            0);
  ASSERT_EQ(run_cli("remesh " + mesh + " -o " + path("detected.obj") + common).code, 0);
  EXPECT_EQ(quadcover::testing::slurp(path("given.obj")), quadcover::testing::slurp(path("detected.obj")));
  const auto batch = run_cli("field " + mesh + " " + quadcover::testing::data_path("cow") + " -o " + path("dir") +
                                 " --save-features " + path("both.txt"),
                             path("e.txt"));
  EXPECT_EQ(batch.code, 2);
  EXPECT_NE(batch.err.find("--save-features: takes one input"), std::string::npos) << batch.err;
  EXPECT_FALSE(fs::exists(path("both.txt")));
}

TEST_F(FeatureAngleCli, NoFeaturesTurnsThemOffInTheFieldAndTheSmoothing) {
  const nlohmann::json none = report("remesh", "fandisk", "", "--no-features");
  const nlohmann::json by_default = report("remesh", "fandisk", "");
  EXPECT_EQ(none["options"]["feature_angle"], 0.0);
  EXPECT_EQ(none["field"]["features"]["sharp_edges"], 0);
  EXPECT_EQ(none["quad_smoothing"]["feature_vertices"], 0);  // no vertex snapped onto a crease it was told to ignore
  EXPECT_GT(by_default["quad_smoothing"]["feature_vertices"].get<int>(), 0);
}

TEST_F(FeatureAngleCli, BadFeatureFileIsRefusedNamingItsLine) {
  const std::string mesh = quadcover::testing::data_path("fandisk");
  const auto refused = [&](const std::string& text, const std::string& message, const std::string& extra = "") {
    SCOPED_TRACE(text);
    {
      std::ofstream file(path("bad.txt"));
      file << text;
    }
    const std::string out = path("refused.obj");
    const auto r =
        run_cli("remesh " + mesh + " -o " + out + " -q --features " + path("bad.txt") + extra, path("e.txt"));
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  };
  refused("1 2 3\n", "bad.txt:1: expected two vertex numbers");
  refused("# header\n\n1\n", "bad.txt:3: expected two vertex numbers");
  refused("0 1\n", "bad.txt:1: vertex numbers count from 1");
  refused("5 5\n", "bad.txt:1: an edge needs two different vertices");
  refused("1 99999999\n", "bad.txt:1: vertex 99999999 is not in the mesh");
  refused("1 2\n1 6000\n", "bad.txt:2: vertices 1 and 6000 are not joined by an edge of the mesh");
  refused("1 2\n", "excludes", " --feature-angle 20");
  refused("1 2\n", "excludes", " --no-features");
  const auto missing = run_cli("remesh " + mesh + " -o " + path("x.obj") + " --features " + path("none.txt"));
  EXPECT_EQ(missing.code, 2);
  EXPECT_FALSE(fs::exists(path("x.obj")));
}

TEST_F(FeatureAngleCli, OutOfRangeIsRefusedBeforeAnyWork) {
  for (const std::string command : {"param", "remesh"})
    for (const std::string angle : {"180.5", "-1", "abc", "nan", "35deg"}) {
      SCOPED_TRACE(command + " " + angle);
      const std::string out = path("refused.obj");
      const auto r = run_cli(
          command + " " + quadcover::testing::data_path("fandisk") + " -o " + out + " --feature-angle " + angle + " -q",
          path("err.txt"));
      EXPECT_EQ(r.code, 2);
      EXPECT_NE(r.err.find("--feature-angle"), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out));
    }
  EXPECT_EQ(run_cli("param " + quadcover::testing::data_path("fandisk") + " -o " + path("ok.obj") +
                    " --optimize none --feature-angle 180 -q")
                .code,
            0);
}

}  // namespace
