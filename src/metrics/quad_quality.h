#pragma once
// Regularity of a quad (or polygon) mesh as reported in thesis Table 7.1: relative standard deviation (RSD) of
// edge lengths and of corner angles, valences and irregular vertices, non-quad faces.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <vector>

#include "mesh/surface_counts.h"
#include "quad/quad_mesh.h"

namespace quadcover {

struct QuadQuality {
  int vertices = 0, faces = 0, quads = 0;
  int non_quads = 0;                ///< faces with a corner count other than 4
  std::map<int, int> face_sizes;    ///< corner count -> number of faces
  double mean_edge_length = 0;
  double rsd_edge_length = 0;       ///< 100 · std / mean over the undirected edges, in percent (Table 7.1)
  double mean_corner_angle = 0;     ///< radians
  double rsd_corner_angle = 0;      ///< 100 · std / mean over all face corners, in percent (Table 7.1)
  std::map<int, int> valence_histogram;  ///< interior vertices: number of edges -> count
  int irregular_vertices = 0;       ///< interior vertices with valence ≠ 4 (Table 7.1's singularities)
  int boundary_vertices = 0;
  int irregular_boundary_vertices = 0;  ///< boundary vertices with valence ∉ {2, 3}
  SurfaceCounts topology;               ///< manifold, boundary loops, components, genus: mesh/surface_counts.h
};

/// Quality of the polygon mesh (V #V by 3, faces counter-clockwise). Standard deviations are population ones.
/// \pre every face index is a row of V.
QuadQuality quad_quality(const Eigen::MatrixX3d& V, const std::vector<std::vector<int>>& faces);
inline QuadQuality quad_quality(const QuadMesh& q) { return quad_quality(q.V, q.faces); }  ///< \pre as above.

/// Relative standard deviation in percent: 100 · sqrt(mean((x - mean)²)) / mean; 0 for an empty list. \pre none
double relative_std_percent(const std::vector<double>& x);

}  // namespace quadcover
