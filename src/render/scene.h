#pragma once
// What the renderer draws, taken from a file as read (a parameterized OBJ with per-corner `vt`, or a polygon mesh).
#include <Eigen/Core>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

struct MeshScene {
  Eigen::MatrixX3d V;                      ///< #V by 3 positions
  std::vector<std::vector<int>> polygons;  ///< faces as read (0-based)
  bool all_triangles = true;               ///< every face has three corners
  Eigen::MatrixX3i F;                      ///< triangles: the faces, polygons fan-triangulated
  Eigen::MatrixX3cd uv;                    ///< #F by 3 per-corner u + iv; empty unless every corner has a `vt`
};

/// Builds the scene from a soup. No manifold check (pictures of broken meshes are useful too).
/// \throw InputError naming the face's file and line for an index out of range or a face with < 3 corners.
MeshScene scene_from_soup(const PolygonSoup& soup);

/// 3D area of each triangle of scene.F, computed as Mesh::face_areas() is (½‖(p1 − p0) × (p2 − p0)‖), so that the
/// flip classification of `render` matches the reports' bit for bit. \pre scene from scene_from_soup.
Eigen::VectorXd triangle_areas(const MeshScene& scene);

}  // namespace quadcover
