// Issue 18 ("never lose data, never say something false") through the real binary: outputs that are inputs, output
// formats by extension, output folders checked before the work, random bytes, `repair`, unreferenced vertices,
// standard input/output, --skip-existing and termination by a signal. Each test is one item of the issue.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "support/cli_runner.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;
using quadcover::testing::CliRun;
using quadcover::testing::slurp;
constexpr std::size_t kFaces = 32;  // make_ellipsoid(1)

class HardeningCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        quadcover::testing::fresh_dir("hardening_cli", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  CliRun run(const std::string& args) const { return quadcover::testing::run_cli(args, path("stderr.txt"), 240); }

  /// A small closed mesh (ellipsoid, kFaces triangles) written as OBJ.
  std::string small_mesh(const std::string& name) const {
    const Mesh m = testing::make_ellipsoid(1, 1.0, 0.8, 0.6);
    write_obj(path(name), m.V(), m.F());
    return path(name);
  }

  /// No temporary file (".NAME.tmpPID.N") anywhere under the test folder.
  void expect_no_temporaries() const {
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "temporary left: " << e.path();
  }

  fs::path dir_;
};

// Item 1: an output that is the input (same name, another spelling, a hard or a symbolic link) is refused before
// the work, the input is untouched; --overwrite-input allows it.
TEST_F(HardeningCli, OutputThatIsAnInputIsRefused) {
  const std::string in = small_mesh("m.obj");
  const std::string before = slurp(in);
  fs::create_hard_link(in, path("hard.obj"));
  fs::create_symlink(in, path("soft.obj"));
  for (const std::string& out : {in, (dir_ / "." / "m.obj").string(), path("hard.obj"), path("soft.obj")}) {
    for (const char* command : {"repair", "remesh", "param"}) {
      const CliRun r = run(std::string(command) + " " + in + " -o " + out);
      EXPECT_EQ(r.code, 2) << command << " -o " << out << ": " << r.err;
      EXPECT_NE(r.err.find("refusing to replace the input file"), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("--overwrite-input"), std::string::npos) << r.err;
      EXPECT_EQ(slurp(in), before) << command << " -o " << out << " changed the input";
    }
  }
  // Other report outputs too (--report of remesh is checked the same way).
  const CliRun report = run("remesh " + in + " -o " + path("q.obj") + " --report " + path("hard.obj"));
  EXPECT_EQ(report.code, 2) << report.err;
  EXPECT_EQ(slurp(in), before);
  EXPECT_FALSE(fs::exists(path("q.obj")));

  const CliRun allowed = run("repair " + in + " -o " + in + " --overwrite-input");
  EXPECT_EQ(allowed.code, 0) << allowed.err;
  EXPECT_TRUE(read_mesh(in).num_faces() == kFaces);
  expect_no_temporaries();
}

// Item 1 in a batch: the file whose output would replace another input fails; the others are written.
TEST_F(HardeningCli, BatchOutputThatIsAnotherInputIsRefused) {
  const std::string a = small_mesh("a.obj");
  const std::string victim = small_mesh("a.repaired.obj");  // a.obj's default output name
  const std::string before = slurp(victim);
  const CliRun r = run("repair " + a + " " + victim + " --json");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(slurp(victim), before);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["failed"], 1);
  EXPECT_TRUE(fs::exists(path("a.repaired.repaired.obj")));
  expect_no_temporaries();
}

// Item 4: the extension of -o names the format written; an unknown one fails before the work with no file.
TEST_F(HardeningCli, OutputFormatFollowsTheExtension) {
  const std::string in = small_mesh("m.obj");
  for (const char* ext : {"obj", "off", "ply", "stl"}) {
    const std::string out = path(std::string("r.") + ext);
    const CliRun r = run("repair " + in + " -o " + out);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string bytes = slurp(out);
    EXPECT_EQ(guess_mesh_format(bytes), ext) << "wrote another format under ." << ext;
    const PolygonSoup soup = read_mesh(out);
    EXPECT_EQ(soup.num_faces(), kFaces) << ext;
  }
  const CliRun bad = run("repair " + in + " -o " + path("r.xyz"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("unsupported output format '.xyz'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("r.xyz")));
}

// Item 13: output folders are created before the work; a folder that cannot be created fails at once.
TEST_F(HardeningCli, OutputFoldersAreCreatedOrRefusedFirst) {
  const std::string a = small_mesh("a.obj"), b = small_mesh("b.obj");
  const CliRun made = run("repair " + a + " " + b + " -o " + path("new/deeper"));
  EXPECT_EQ(made.code, 0) << made.err;
  EXPECT_TRUE(fs::exists(path("new/deeper/a.repaired.obj")));
  EXPECT_TRUE(fs::exists(path("new/deeper/b.repaired.obj")));
  const CliRun single = run("repair " + a + " -o " + path("other/one.off"));
  EXPECT_EQ(single.code, 0) << single.err;
  EXPECT_TRUE(fs::exists(path("other/one.off")));

  { std::ofstream(path("plainfile")) << "x"; }
  for (const std::string& out : {path("plainfile/sub"), path("plainfile")}) {
    const CliRun r = run("remesh " + a + " " + b + " -o " + out);
    EXPECT_EQ(r.code, 2) << out;
    EXPECT_NE(r.err.find("--output"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("[1/2]"), std::string::npos) << "the files were processed before the check:\n" << r.err;
  }
  const CliRun folder_for_one = run("repair " + a + " -o " + path("new"));
  EXPECT_EQ(folder_for_one.code, 2);
  EXPECT_NE(folder_for_one.err.find("this is a folder"), std::string::npos) << folder_for_one.err;
}

// Item 14: random bytes are "not a mesh file" (exit 2), never an empty mesh that is manifold and orientable.
TEST_F(HardeningCli, RandomBytesAreNotAMesh) {
  std::mt19937 rng(18);
  std::string bytes(4096, '\0');
  for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
  for (const char* ext : {"obj", "off", "ply", "stl"}) {
    const std::string p = path(std::string("garbage.") + ext);
    { std::ofstream(p, std::ios::binary) << bytes; }
    for (const char* json : {"", " --json"}) {
      const CliRun r = run(std::string("info ") + p + json);
      EXPECT_EQ(r.code, 2) << ext << ": " << r.out << r.err;
      EXPECT_EQ(r.out.find("manifold"), std::string::npos) << ext << ": " << r.out;
      EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    }
  }
  const CliRun obj = run("info " + path("garbage.obj"));
  EXPECT_NE(obj.err.find("not an OBJ mesh file"), std::string::npos) << obj.err;
}

// Item 15: the repairs the validation messages suggest exist where they are suggested: `quadcover repair`.
TEST_F(HardeningCli, RepairDoesWhatTheMessagesSuggest) {
  const std::string blobby = testing::data_path("bad/blobby_inconsistent_orientation");
  const CliRun info = run("info " + blobby);
  EXPECT_EQ(info.code, 2);
  EXPECT_NE(info.err.find("quadcover repair"), std::string::npos) << info.err;
  const CliRun fixed = run("repair " + blobby + " -o " + path("blobby.obj") + " --json");
  ASSERT_EQ(fixed.code, 0) << fixed.err;
  EXPECT_GT(nlohmann::json::parse(fixed.out)["flipped_faces"].get<int>(), 0);
  EXPECT_EQ(run("info " + path("blobby.obj")).code, 0);

  const std::string quads = testing::data_path("bad/spot_quads_nontriangle");
  EXPECT_NE(run("info " + quads).err.find("quadcover repair"), std::string::npos);
  const CliRun tri = run("repair " + quads + " -o " + path("spot.ply") + " --json");
  ASSERT_EQ(tri.code, 0) << tri.err;
  EXPECT_EQ(nlohmann::json::parse(tri.out)["faces"], 2 * 2928);
  EXPECT_EQ(run("info " + path("spot.ply")).code, 0);

  // Faces that carry no surface: a zero-area cap (its edge flipped), a repeated vertex, a repeated face. The
  // messages point to repair, which removes them and says how many; the result is valid with the input's topology.
  struct Degenerate {
    const char* file;
    const char* counter;
    int genus, faces;
  };
  for (const Degenerate& d : {Degenerate{"fertility_zero_area_face", "zero_area_faces_flipped", 4, 9000},
                              Degenerate{"spot_degenerate_face", "repeated_vertex_faces_dropped", 0, 5856},
                              Degenerate{"spot_duplicate_face", "duplicate_faces_dropped", 0, 5856}}) {
    SCOPED_TRACE(d.file);
    const std::string in = testing::data_path(std::string("bad/") + d.file);
    EXPECT_NE(run("info " + in).err.find("quadcover repair"), std::string::npos);
    const CliRun r = run("repair " + in + " -o " + path("fixed.obj") + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j[d.counter], 1);
    EXPECT_EQ(j["faces"], d.faces);
    const CliRun check = run("info " + path("fixed.obj") + " --json");
    ASSERT_EQ(check.code, 0) << check.err;
    const nlohmann::json i = nlohmann::json::parse(check.out);
    EXPECT_EQ(i["genus"], d.genus);
    EXPECT_TRUE(i["manifold"].get<bool>());
  }

  // What cannot be repaired: exit 2, the problems listed, nothing written.
  const CliRun klein = run("repair " + testing::data_path("bad/torus_klein_nonorientable") + " -o " + path("k.obj"));
  EXPECT_EQ(klein.code, 2);
  EXPECT_NE(klein.err.find("not orientable"), std::string::npos) << klein.err;
  EXPECT_FALSE(fs::exists(path("k.obj")));
}

// Item 16: dropped unreferenced vertices are said on stderr (one input, in a batch and with -q).
TEST_F(HardeningCli, DroppedUnreferencedVerticesAreAWarning) {
  const Mesh m = testing::make_ellipsoid(1);
  write_obj(path("iso.obj"), m.V(), m.F());
  { std::ofstream(path("iso.obj"), std::ios::app) << "v 5 5 5\nv 6 6 6\n"; }
  const CliRun one = run("field " + path("iso.obj") + " -o " + path("iso.json"));
  EXPECT_EQ(one.code, 0) << one.err;
  EXPECT_NE(one.err.find("warning: " + path("iso.obj") + ": 2 unreferenced vertices"), std::string::npos) << one.err;
  fs::copy(path("iso.obj"), path("iso2.obj"));
  const CliRun batch = run("field " + path("iso.obj") + " " + path("iso2.obj") + " -o " + path("out"));
  EXPECT_EQ(batch.code, 0) << batch.err;
  EXPECT_NE(batch.err.find(path("iso2.obj") + ": 2 unreferenced vertices"), std::string::npos) << batch.err;
  const CliRun quiet = run("field " + path("iso.obj") + " -o " + path("iso.json") + " -q");  // -q hides progress only
  EXPECT_NE(quiet.err.find("warning: " + path("iso.obj") + ": 2 unreferenced vertices"), std::string::npos) << quiet.err;
}

// Item 17: "-" reads standard input and writes standard output, in the format of --format.
TEST_F(HardeningCli, StandardInputAndOutput) {
  const std::string in = small_mesh("m.obj");
  const CliRun off = run("repair - -o - --format off < " + in);
  ASSERT_EQ(off.code, 0) << off.err;
  EXPECT_EQ(guess_mesh_format(off.out), "off");
  EXPECT_EQ(read_off_from_memory(off.out, "stdout").num_faces(), kFaces);
  EXPECT_NE(off.err.find("faces: " + std::to_string(kFaces)), std::string::npos) << "the result lines go to stderr:\n"
                                                                                 << off.err;
  EXPECT_FALSE(fs::exists("-"));

  // No -o with standard input: the output goes to standard output; the input format is guessed without --format.
  const CliRun obj = run("repair - < " + in);
  ASSERT_EQ(obj.code, 0) << obj.err;
  EXPECT_EQ(read_obj_from_memory(obj.out, "stdout").num_faces(), kFaces);

  const CliRun info = run("info - --json < " + in);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["faces"], kFaces);

  const CliRun batch = run("repair - " + in);
  EXPECT_EQ(batch.code, 2);
  EXPECT_NE(batch.err.find("one mesh only"), std::string::npos) << batch.err;
}

// Item 19: a re-run replaces outputs (as --help says); --skip-existing leaves them and says so.
TEST_F(HardeningCli, RerunReplacesOutputsUnlessSkipExisting) {
  const std::string a = small_mesh("a.obj"), b = small_mesh("b.obj");
  ASSERT_EQ(run("repair " + a + " " + b + " -o " + path("out")).code, 0);
  { std::ofstream(path("out/a.repaired.obj")) << "marker\n"; }
  const CliRun skip = run("repair " + a + " " + b + " -o " + path("out") + " --skip-existing --json");
  EXPECT_EQ(skip.code, 0) << skip.err;
  const nlohmann::json j = nlohmann::json::parse(skip.out);
  EXPECT_EQ(j["skipped"], 2);
  EXPECT_EQ(slurp(path("out/a.repaired.obj")), "marker\n");
  fs::remove(path("out/b.repaired.obj"));
  const CliRun some = run("repair " + a + " " + b + " -o " + path("out") + " --skip-existing --json");
  EXPECT_EQ(nlohmann::json::parse(some.out)["skipped"], 1);
  EXPECT_TRUE(fs::exists(path("out/b.repaired.obj")));
  const CliRun single = run("repair " + a + " -o " + path("out/a.repaired.obj") + " --skip-existing");
  EXPECT_EQ(single.code, 0);
  EXPECT_NE(single.err.find("skipped"), std::string::npos) << single.err;
  EXPECT_EQ(slurp(path("out/a.repaired.obj")), "marker\n");

  const CliRun replaced = run("repair " + a + " " + b + " -o " + path("out"));
  EXPECT_EQ(replaced.code, 0);
  EXPECT_NE(slurp(path("out/a.repaired.obj")), "marker\n");
  const CliRun help = run("repair --help");
  EXPECT_NE(help.out.find("replaced"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("never overwritten"), std::string::npos) << help.out;
}

// Item 12: messages quote vertex indices as the file writes them and count faces from 1.
TEST_F(HardeningCli, ErrorsNumberElementsAsTheFileDoes) {
  { std::ofstream(path("neg.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -5\n"; }
  const CliRun neg = run("info " + path("neg.obj"));
  EXPECT_EQ(neg.code, 2);
  EXPECT_NE(neg.err.find("vertex -5"), std::string::npos) << neg.err;
  EXPECT_NE(neg.err.find("neg.obj:4"), std::string::npos) << neg.err;
  { std::ofstream(path("far.obj")) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 9\n"; }
  const CliRun far = run("info " + path("far.obj"));
  EXPECT_NE(far.err.find("face 2 (0-based 1, " + path("far.obj") + ":5): vertex index 9"), std::string::npos)
      << far.err;
  { std::ofstream(path("far.off")) << "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 7\n"; }
  const CliRun off = run("info " + path("far.off"));
  EXPECT_NE(off.err.find("face 2 (0-based 1, " + path("far.off") + ":7): vertex index 7"), std::string::npos)
      << off.err;
}

// Item 3: SIGTERM and SIGHUP stop a run at once with 128 + signal, leaving neither the output nor a temporary.
TEST_F(HardeningCli, TerminationSignalLeavesNoFile) {
  const std::string in = testing::data_path("bunny_20k_holes");
  for (const int sig : {SIGTERM, SIGHUP}) {
    const std::string out = path("q.obj");
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, 1);
      ::dup2(null, 2);
      ::execl(QUADCOVER_CLI, QUADCOVER_CLI, "remesh", in.c_str(), "-o", out.c_str(), "--report", path("q.json").c_str(),
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    ::kill(pid, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status) << " instead of exiting";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(path("q.json")));
    expect_no_temporaries();
  }
}

}  // namespace
}  // namespace quadcover
