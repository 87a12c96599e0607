// Batch output names (issue 8): inputs sharing a file name never overwrite each other's output. The rule of
// batch_output_stems (parent folder, extension, then _2, _3, ...) and the real binary on colliding inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli/common.h"
#include "io/read_mesh.h"
#include "io/write_off.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using quadcover::cli::batch_output_path;
using quadcover::cli::batch_output_stems;
using quadcover::cli::expand_inputs;
using quadcover::testing::run_cli;
using quadcover::testing::slurp;
using Names = std::vector<std::string>;

fs::path fresh_dir(const std::string& name) { return quadcover::testing::fresh_dir("batch_names", name); }

TEST(BatchNames, DistinctStemsKeepTheirNames) {
  EXPECT_EQ(batch_output_stems({"a/bunny.obj", "b/cow.off", "spot.ply"}, "out"), (Names{"bunny", "cow", "spot"}));
  EXPECT_EQ(batch_output_stems({"a/bunny.obj", "b/bunny.obj"}, ""), (Names{"bunny", "bunny"}));  // own folders
}

TEST(BatchNames, SameStemGetsParentFolderOrExtension) {
  EXPECT_EQ(batch_output_stems({"a/bunny.obj", "b/bunny.obj"}, "out"), (Names{"a_bunny", "b_bunny"}));
  EXPECT_EQ(batch_output_stems({"m/bunny.obj", "m/bunny.off"}, ""), (Names{"bunny_obj", "bunny_off"}));
  EXPECT_EQ(batch_output_stems({"m/bunny.obj", "m/bunny.off"}, "out"), (Names{"bunny_obj", "bunny_off"}));
  // Both rules at once; an unrelated file keeps its plain name.
  EXPECT_EQ(batch_output_stems({"a/bunny.obj", "b/bunny.off", "c/cow.obj"}, "out"),
            (Names{"a_bunny_obj", "b_bunny_off", "cow"}));
}

TEST(BatchNames, RemainingClashesAreNumberedInInputOrder) {
  // Same parent folder name and extension: nothing tells them apart but their order.
  EXPECT_EQ(batch_output_stems({"x/a/bunny.obj", "y/a/bunny.obj", "z/a/bunny.obj"}, "out"),
            (Names{"bunny", "bunny_2", "bunny_3"}));
  // A made name that another input has as its own: the plain name wins, the made one is numbered.
  EXPECT_EQ(batch_output_stems({"a/bunny.obj", "b/bunny.obj", "c/a_bunny.obj"}, "out"),
            (Names{"a_bunny_2", "b_bunny", "a_bunny"}));
}

TEST(BatchNames, AlwaysDistinctPerOutputFolder) {
  // Every combination of 3 folders (two with the same name) x 3 stems x 3 extensions, in a scrambled order.
  Names files;
  for (const char* dir : {"p/a", "q/a", "b"})
    for (const char* stem : {"m", "a_m", "m_obj"})
      for (const char* ext : {".obj", ".off", ".ply"}) files.push_back(std::string(dir) + "/" + stem + ext);
  for (std::size_t i = 0; i < files.size(); ++i) std::swap(files[i], files[(i * 7 + 3) % files.size()]);
  for (const std::string out : {"out", ""}) {
    const Names names = batch_output_stems(files, out);
    ASSERT_EQ(names.size(), files.size());
    std::set<std::string> seen;
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string folder = out.empty() ? fs::path(files[i]).parent_path().string() : out;
      EXPECT_TRUE(seen.insert(folder + "/" + names[i]).second) << files[i] << " -> " << names[i];
    }
    EXPECT_EQ(batch_output_stems(files, out), names);  // deterministic
  }
}

TEST(BatchNames, FileNamedTwiceIsProcessedOnce) {
  const fs::path dir = fresh_dir("twice");
  fs::copy_file(quadcover::testing::data_path("torus_5k"), dir / "t.obj");
  const std::string t = (dir / "t.obj").string(), dotted = (dir / "." / "t.obj").string();
  EXPECT_EQ(expand_inputs({t, dotted, dir.string()}), (Names{t}));
  fs::remove_all(dir);
}

TEST(BatchNames, OutputPathOutsideABatchIsThePlainStem) {
  EXPECT_EQ(batch_output_path("a/bunny.obj", "out", ".param.obj"), "out/bunny.param.obj");
}

// The real binary: a/m.obj and b/m.obj (different meshes) and m.obj / m.off in one folder, with -o FOLDER.
TEST(BatchNames, CollidingInputsWriteDistinctOutputsWithAnyJobCount) {
  const fs::path dir = fresh_dir("cli");
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  fs::copy_file(quadcover::testing::data_path("torus_5k"), dir / "a" / "m.obj");
  fs::copy_file(quadcover::testing::data_path("eight_genus2"), dir / "b" / "m.obj");
  fs::copy_file(quadcover::testing::data_path("eight_genus2"), dir / "c.obj");
  const quadcover::PolygonSoup torus = quadcover::read_mesh(quadcover::testing::data_path("torus_5k"));
  quadcover::write_off((dir / "c.off").string(), torus);
  const std::string inputs = (dir / "a" / "m.obj").string() + " " + (dir / "b" / "m.obj").string() + " " +
                             (dir / "c.obj").string() + " " + (dir / "c.off").string();
  const Names expected = {"a_m.field.json", "b_m.field.json", "c_obj.field.json", "c_off.field.json"};

  std::map<std::string, std::string> first;
  for (const char* jobs : {"1", "2"}) {
    const fs::path out = dir / (std::string("out") + jobs);
    fs::create_directories(out);
    const auto r = run_cli("field --json -j " + std::string(jobs) + " -o " + out.string() + " " + inputs);
    ASSERT_EQ(r.code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["files"].size(), 4u);  // the summary lists every input
    EXPECT_EQ(j["succeeded"], 4);
    std::set<std::string> outputs;
    for (const auto& f : j["files"]) outputs.insert(f["result"]["output"].get<std::string>());
    EXPECT_EQ(outputs.size(), 4u);
    std::set<std::string> contents;
    for (const std::string& name : expected) {
      ASSERT_TRUE(fs::exists(out / name)) << name;
      EXPECT_EQ(outputs.count((out / name).string()), 1u) << name;
      const std::string c = slurp(out / name);
      contents.insert(c);
      if (first.count(name))
        EXPECT_EQ(c, first[name]) << name << " differs between -j1 and -j2";
      else
        first[name] = c;
    }
    EXPECT_EQ(contents.size(), 4u);  // four different results, none overwritten
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 4);
  }
  fs::remove_all(dir);
}

}  // namespace
