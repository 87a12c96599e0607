// Writers: exact round trips (shortest round-trip number formatting) and atomicity (a failing writer leaves
// neither a partial file nor a temporary behind, and never clobbers an existing file).
#include "io/write_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "io/read_mesh.h"
#include "io_test_util.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// Faces of a triangle soup as an #F by 3 matrix.
Eigen::MatrixX3i triangles(const PolygonSoup& soup) {
  Eigen::MatrixX3i F(static_cast<Eigen::Index>(soup.num_faces()), 3);
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) F(static_cast<Eigen::Index>(f), k) = static_cast<int>(soup.face_begin(f)[k]);
  return F;
}

std::size_t files_in(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(WriteObj, RealMeshRoundTripIsBitExact) {
  TempDir dir;
  const PolygonSoup in = read_obj(testing::data_path("fertility_genus4"));
  write_obj(dir.file("out.obj"), in.positions, triangles(in));
  const PolygonSoup out = read_obj(dir.file("out.obj"));
  EXPECT_EQ(out.positions, in.positions);  // exact, not approximate
  EXPECT_EQ(out.face_vertices, in.face_vertices);
}

TEST(WriteObj, ExtremeValuesRoundTrip) {
  TempDir dir;
  Eigen::MatrixX3d V(4, 3);
  V << 0.1, 1.0 / 3.0, -2.5e-300, std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min(),
      -0.0, 1e9 + 0.123456789, -1e-9 * std::acos(-1.0), 7, 123456789012345678.0, 5e-324, 1;
  Eigen::MatrixX3i F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  write_obj(dir.file("x.obj"), V, F);
  const PolygonSoup out = read_obj(dir.file("x.obj"));
  ASSERT_EQ(out.positions.rows(), 4);
  for (Eigen::Index i = 0; i < V.size(); ++i) EXPECT_EQ(out.positions(i), V(i)) << i;
}

TEST(WriteObj, PerCornerUvRoundTrip) {
  TempDir dir;
  const Mesh mesh = testing::make_grid(6);
  // A seam-like layout: every face has its own three uv corners (random values).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  Eigen::MatrixX2d UV(3 * mesh.num_faces(), 2);
  for (Eigen::Index i = 0; i < UV.size(); ++i) UV(i) = u(rng);
  Eigen::MatrixX3i FUV(mesh.num_faces(), 3);
  for (int f = 0; f < mesh.num_faces(); ++f) FUV.row(f) << 3 * f + 2, 3 * f, 3 * f + 1;
  write_obj_with_uv(dir.file("uv.obj"), mesh.V(), mesh.F(), UV, FUV);
  const PolygonSoup soup = read_obj(dir.file("uv.obj"));
  ASSERT_TRUE(soup.has_uv());
  EXPECT_EQ(soup.uv, UV);
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(soup.face_uv[static_cast<std::size_t>(3 * f + k)], FUV(f, k));
      ASSERT_EQ(soup.face_vertices[static_cast<std::size_t>(3 * f + k)], mesh.F()(f, k));
    }
  // And the soup writer reproduces the same file content.
  write_soup_obj(dir.file("again.obj"), soup);
  EXPECT_EQ(read_file_bytes(dir.file("again.obj")), read_file_bytes(dir.file("uv.obj")));
}

TEST(WritePolygonObj, QuadsRoundTrip) {
  TempDir dir;
  Eigen::MatrixX3d V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0;
  const std::vector<std::vector<int>> faces = {{0, 1, 4, 3}, {1, 2, 5}, {1, 5, 4}};
  write_polygon_obj(dir.file("q.obj"), V, faces);
  const PolygonSoup soup = read_obj(dir.file("q.obj"));
  ASSERT_EQ(soup.num_faces(), 3u);
  EXPECT_EQ(soup.face_size(0), 4u);
  EXPECT_EQ(soup.face_vertices, (std::vector<std::int64_t>{0, 1, 4, 3, 1, 2, 5, 1, 5, 4}));
  EXPECT_EQ(soup.positions, V);
}

TEST(AtomicWrite, FailingWriterLeavesNoFile) {
  TempDir dir;
  Eigen::MatrixX3d V = Eigen::MatrixX3d::Random(500, 3);
  Eigen::MatrixX3i F = Eigen::MatrixX3i::Zero(400, 3);
  for (int f = 0; f < 400; ++f) F.row(f) << f, f + 1, f + 2;
  F(399, 2) = 500;  // out of range: detected after most of the file has been written
  EXPECT_THROW(write_obj(dir.file("bad.obj"), V, F), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir.file("bad.obj")));
  EXPECT_EQ(files_in(dir.path()), 0u) << "temporary file left behind";
}

TEST(AtomicWrite, FailureKeepsThePreviousFile) {
  TempDir dir;
  testing::write_text(dir.file("keep.obj"), "previous content\n");
  EXPECT_THROW(write_file_atomically(dir.file("keep.obj"),
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw std::runtime_error("cancelled");
                                     }),
               std::runtime_error);
  EXPECT_EQ(read_file_bytes(dir.file("keep.obj")), "previous content\n");
  EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(AtomicWrite, SuccessReplacesTheFile) {
  TempDir dir;
  testing::write_text(dir.file("a.txt"), "old");
  write_file_atomically(dir.file("a.txt"), [](std::ostream& out) { out << "new"; });
  EXPECT_EQ(read_file_bytes(dir.file("a.txt")), "new");
  EXPECT_EQ(files_in(dir.path()), 1u);
}

TEST(AtomicWrite, UnwritableDirectoryIsAnInputError) {
  TempDir dir;
  const std::string path = dir.file("no/such/dir/out.obj");
  const InputError e = testing::expect_input_error([&] { write_file_atomically(path, [](std::ostream& o) { o << 1; }); });
  EXPECT_EQ(e.file(), path);
}

TEST(WriteObjWithUv, MismatchedSizesThrow) {
  TempDir dir;
  const Mesh mesh = testing::make_grid(2);
  const Eigen::MatrixX2d UV = Eigen::MatrixX2d::Zero(3, 2);
  Eigen::MatrixX3i FUV = Eigen::MatrixX3i::Zero(mesh.num_faces() - 1, 3);
  EXPECT_THROW(write_obj_with_uv(dir.file("m.obj"), mesh.V(), mesh.F(), UV, FUV), std::invalid_argument);
  FUV = Eigen::MatrixX3i::Constant(mesh.num_faces(), 3, 3);  // uv index 3 of 3
  EXPECT_THROW(write_obj_with_uv(dir.file("m.obj"), mesh.V(), mesh.F(), UV, FUV), std::invalid_argument);
  EXPECT_EQ(files_in(dir.path()), 0u);
}

}  // namespace
}  // namespace quadcover

namespace quadcover {
namespace {

// A 2 x 1 strip of quads (6 vertices) for the polygon writers.
struct QuadStrip {
  Eigen::MatrixX3d V{6, 3};
  std::vector<std::vector<int>> faces{{0, 1, 4, 3}, {1, 2, 5, 4}};
  QuadStrip() { V << 0, 0, 0, 1, 0, 0, 2, 0, 0.5, 0, 1, 0, 1, 1, 0, 2, 1, 0.25; }
};

// Issue 18 item 4: write_polygon_mesh writes the format the extension names; every format reads back to the same
// positions and (for OBJ, OFF, PLY) the same polygons; STL triangulates and says how many polygons it split.
TEST(WritePolygonMesh, FormatFollowsTheExtensionAndReadsBack) {
  TempDir dir;
  const QuadStrip q;
  for (const char* ext : {"obj", "off", "ply", "OFF"}) {
    const std::string path = dir.file(std::string("q.") + ext);
    EXPECT_EQ(write_polygon_mesh(path, q.V, q.faces), 0u);
    const PolygonSoup soup = read_mesh(path);
    EXPECT_EQ(guess_mesh_format(read_file_bytes(path)), file_extension(path)) << ext;
    EXPECT_EQ(soup.positions, q.V) << ext;
    EXPECT_EQ(soup.face_vertices, (std::vector<std::int64_t>{0, 1, 4, 3, 1, 2, 5, 4})) << ext;
  }
  const std::string stl = dir.file("q.stl");
  EXPECT_EQ(write_polygon_mesh(stl, q.V, q.faces), 2u);
  const PolygonSoup tri = read_mesh(stl);
  EXPECT_EQ(tri.num_faces(), 4u);
  EXPECT_EQ(tri.num_vertices(), 6u);  // welded back: the same six corners
  // The same fan triangles (corner 0 with each consecutive pair), positions rounded to float32 by binary STL.
  auto area = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return 0.5 * (b - a).cross(c - a).norm();
  };
  double written = 0, expected = 0;
  for (std::size_t f = 0; f < tri.num_faces(); ++f)
    written += area(tri.positions.row(tri.face_begin(f)[0]), tri.positions.row(tri.face_begin(f)[1]),
                    tri.positions.row(tri.face_begin(f)[2]));
  for (const auto& face : q.faces)
    for (std::size_t k = 1; k + 1 < face.size(); ++k)
      expected += area(q.V.row(face[0]), q.V.row(face[k]), q.V.row(face[k + 1]));
  EXPECT_NEAR(written, expected, 1e-6);
}

TEST(WritePolygonMesh, UnknownExtensionIsRefusedWithoutAFile) {
  TempDir dir;
  const QuadStrip q;
  for (const char* name : {"q.xyz", "q", "q.obj.bak"}) {
    EXPECT_THROW(mesh_output_format(dir.file(name)), InputError) << name;
    EXPECT_THROW(write_polygon_mesh(dir.file(name), q.V, q.faces), InputError) << name;
  }
  EXPECT_EQ(files_in(dir.path()), 0u);
  EXPECT_EQ(mesh_output_format("a/b.Ply"), "ply");
}

// Issue 18 item 3: remove_temporary_files (what the CLI's signal handlers call) removes the temporary of a write in
// progress, and a write's temporary is registered before the file exists.
TEST(AtomicFile, TemporaryOfAnUnfinishedWriteIsRemovedOnRequest) {
  TempDir dir;
  std::size_t during = 0, after_cleanup = 0;
  EXPECT_THROW(write_file_atomically(dir.file("out.txt"),
                                     [&](std::ostream& out) {
                                       out << "partial" << std::flush;
                                       during = files_in(dir.path());
                                       remove_temporary_files();
                                       after_cleanup = files_in(dir.path());
                                       throw std::runtime_error("stop");
                                     }),
               std::runtime_error);
  EXPECT_EQ(during, 1u);
  EXPECT_EQ(after_cleanup, 0u);
  EXPECT_EQ(files_in(dir.path()), 0u);
  remove_temporary_files();  // nothing registered any more: a no-op
  write_file_atomically(dir.file("ok.txt"), [](std::ostream& out) { out << "ok"; });
  remove_temporary_files();
  EXPECT_TRUE(fs::exists(dir.file("ok.txt")));
}

TEST(AtomicFile, OutputGuardRefusesBeforeAnythingIsCreated) {
  TempDir dir;
  set_output_guard([](const std::string& path) {
    if (path.ends_with("no.txt")) throw InputError(path, 0, "refused");
  });
  EXPECT_THROW(write_file_atomically(dir.file("no.txt"), [](std::ostream& out) { out << "x"; }), InputError);
  write_file_atomically(dir.file("yes.txt"), [](std::ostream& out) { out << "x"; });
  set_output_guard({});
  EXPECT_EQ(files_in(dir.path()), 1u);
  EXPECT_TRUE(fs::exists(dir.file("yes.txt")));
}

}  // namespace
}  // namespace quadcover
