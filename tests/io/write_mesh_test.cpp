// Writers: exact round trips (shortest round-trip number formatting) and atomicity (a failing writer leaves
// neither a partial file nor a temporary behind, and never clobbers an existing file).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "io/atomic_file.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
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
