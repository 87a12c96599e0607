#pragma once
// Helpers shared by the calculus tests: cached real meshes, deterministic random functions and fields.
#include <map>
#include <random>
#include <string>

#include "calculus/vector_field.h"
#include "support/test_meshes.h"

namespace quadcover::testing {

/// The real meshes the calculus identities are checked on (genus 0-4, closed and with boundary).
inline const char* const kCalculusMeshes[] = {"bunny_3k",         "torus_5k",    "eight_genus2",    "3holes_genus3",
                                              "fertility_genus4", "lilium_disk", "mech_holes_shark"};

/// Loads tests/data/NAME.obj once per test process.
inline const Mesh& cached_mesh(const std::string& name) {
  static std::map<std::string, Mesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, load_test_mesh(name)).first;
  return it->second;
}

/// Uniform entries in [-1, 1], reproducible from `seed`.
inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = 2.0 * (static_cast<double>(rng()) / 4294967295.0) - 1.0;
  return x;
}

/// A random piecewise constant tangent field, #F.
inline VectorField random_field(const Mesh& mesh, unsigned seed) {
  const Eigen::VectorXd re = random_vector(mesh.num_faces(), seed);
  const Eigen::VectorXd im = random_vector(mesh.num_faces(), seed + 7919);
  VectorField X(mesh.num_faces());
  for (int f = 0; f < mesh.num_faces(); ++f) X[f] = Complex(re[f], im[f]);
  return X;
}

}  // namespace quadcover::testing
