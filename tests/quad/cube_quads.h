#pragma once
// A known closed quad mesh for the tests that edit quad meshes (quadrangulate.h, doublets.h): the extraction of the
// cube map (6·5² planar unit squares), and its faces as corner sets, to compare meshes up to face order and rotation.
#include <gtest/gtest.h>

#include <set>

#include "quad/extract_quads.h"
#include "quad/quad_test_maps.h"

namespace quadcover::testing {

inline QuadMesh cube_quads() {
  const auto [mesh, param] = cube_map(3, 5);
  QuadMesh q = extract_quads(mesh, param).mesh;
  EXPECT_EQ(q.num_faces(), 150);
  return q;
}

inline std::multiset<std::set<int>> face_sets(const QuadMesh& q) {
  std::multiset<std::set<int>> s;
  for (const auto& f : q.faces) s.insert(std::set<int>(f.begin(), f.end()));
  return s;
}

}  // namespace quadcover::testing
