#pragma once
// Test helper: deterministic pseudo-random base sets B of interior vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover::testing {

/// `count` distinct interior vertices drawn with a fixed seed (fewer if the mesh has fewer), sorted.
inline std::vector<int> random_interior_vertices(const Mesh& mesh, int count, unsigned seed) {
  std::vector<int> interior;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (!mesh.is_boundary_vertex(v)) interior.push_back(v);
  std::mt19937 rng(seed);
  std::vector<int> chosen;
  for (int i = 0; i < count && !interior.empty(); ++i) {
    std::uniform_int_distribution<std::size_t> pick(0, interior.size() - 1);
    const std::size_t j = pick(rng);
    chosen.push_back(interior[j]);
    interior[j] = interior.back();
    interior.pop_back();
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

/// A case of the suites on shipped meshes: tests/data/`mesh` with random_interior_vertices(mesh, num_base, seed).
struct BaseSetCase {
  std::string mesh;
  int num_base;
  unsigned seed;
};

/// The case's name in the test list: MESH_B<num_base>.
inline std::string base_set_case_name(const ::testing::TestParamInfo<BaseSetCase>& info) {
  return info.param.mesh + "_B" + std::to_string(info.param.num_base);
}

}  // namespace quadcover::testing
