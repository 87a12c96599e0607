#pragma once
// The mesh a single-mesh benchmark runs on: the first argument left after Google Benchmark's flags, else
// $QUADCOVER_BENCH_MESH, else the repository's tests/data/bunny_20k_holes.obj.
#include <cstdlib>
#include <string>

inline std::string bench_mesh_path(int argc, char** argv) {
  if (argc > 1) return argv[1];
  if (const char* env = std::getenv("QUADCOVER_BENCH_MESH"); env && *env) return env;
  return std::string(QUADCOVER_SOURCE_DIR) + "/tests/data/bunny_20k_holes.obj";
}
