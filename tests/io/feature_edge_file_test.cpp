// Feature edge files (`--features FILE`): vertex pairs counted from 1, comments and blank lines, and every malformed
// line reported with its number.
#include "io/feature_edge_file.h"

#include <gtest/gtest.h>

#include "io_test_util.h"

namespace quadcover {
namespace {

using testing::expect_input_error;

TEST(ReadFeatureEdges, PairsCountFromOneWithCommentsAndBlankLines) {
  const auto edges = read_feature_edges_from_memory("# creases\n1 2\n\n  7\t3  # a comment\r\n10 11", "f.txt");
  ASSERT_EQ(edges.size(), 3u);
  EXPECT_EQ(edges[0].a, 0);
  EXPECT_EQ(edges[0].b, 1);
  EXPECT_EQ(edges[0].line, 2);
  EXPECT_EQ(edges[1].a, 6);
  EXPECT_EQ(edges[1].b, 2);
  EXPECT_EQ(edges[1].line, 4);
  EXPECT_EQ(edges[2].line, 5);  // the last line needs no newline
  EXPECT_TRUE(read_feature_edges_from_memory("# nothing\n\n", "f.txt").empty());
}

TEST(ReadFeatureEdges, MalformedLinesAreNamed) {
  const auto error = [](const char* text) {
    return std::string(expect_input_error([&] { read_feature_edges_from_memory(text, "f.txt"); }).what());
  };
  EXPECT_EQ(error("1 2\n3\n"), "f.txt:2: expected two vertex numbers (an edge of the mesh), counted from 1");
  EXPECT_EQ(error("1 2 3\n"), "f.txt:1: expected two vertex numbers (an edge of the mesh), counted from 1");
  EXPECT_EQ(error("1 x\n"), "f.txt:1: expected two vertex numbers (an edge of the mesh), counted from 1");
  EXPECT_EQ(error("1.5 2\n"), "f.txt:1: expected two vertex numbers (an edge of the mesh), counted from 1");
  EXPECT_EQ(error("\n\n0 4\n"), "f.txt:3: vertex numbers count from 1, got 0");
  EXPECT_EQ(error("3 -2\n"), "f.txt:1: vertex numbers count from 1, got -2");
  EXPECT_EQ(error("3 3\n"), "f.txt:1: an edge needs two different vertices, got 3 twice");
  EXPECT_EQ(error("1 4294967296\n"), "f.txt:1: vertex number 4294967296 is too large");
  EXPECT_EQ(expect_input_error([] { read_feature_edges("/no/such/features.txt"); }).file(), "/no/such/features.txt");
}

}  // namespace
}  // namespace quadcover
