#pragma once
// The triangle mesh every stage reads (thesis 1.1): positions, faces, connectivity and cached intrinsic geometry.
// Immutable after construction; build it with build_mesh() (validates) or Mesh::from_triangles().
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <complex>
#include <span>
#include <vector>

#include "common/quarter_turn.h"
#include "io/polygon_soup.h"
#include "mesh/validate.h"

namespace quadcover {

using Complex = std::complex<double>;

/// The quarter-turn power i^k for any integer k. \pre none
inline Complex ipow(int k) {
  static const Complex table[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  return table[mod4(k)];
}

/// a·b with the arithmetic std::complex uses for finite operands, (ac − bd, ad + bc), without its call to the NaN
/// recovery (__muldc3) per product: for the hot loops. \pre none (infinite or NaN operands give what the formula gives)
inline Complex product(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

/// Per connected component (faces connected through edges): counts and topology, χ = v - e + f (1.1),
/// genus from χ = 2 - 2g - b (1.2 extended to boundaries).
struct ComponentInfo {
  int vertices = 0, edges = 0, faces = 0, boundary_loops = 0;
  int euler_characteristic = 0;
  int genus = 0;
};

/// Conventions (used everywhere in quadcover):
///  - Face f has corners F(f,0), F(f,1), F(f,2), counter-clockwise around the outward normal.
///  - Face edge k of f is the edge *opposite* corner k, running from corner k+1 to corner k+2 (mod 3).
///  - Edge e runs from E(e,0) to E(e,1) with E(e,0) < E(e,1). FE_sign(f,k) = +1 if face f traverses its edge k
///    in that direction, -1 otherwise.
///  - EF(e,0) is the face traversing e positively (e is positively oriented in it: it lies to the left of e),
///    EF(e,1) the face traversing it negatively; -1 where there is none (boundary).
///    For an interior edge, s = EF(e,0) and t = EF(e,1) are the "s" and "t" of thesis (1.6).
///  - Each face has a tangent basis (b1, b2): b1 = unit(p1 - p0), b2 = n × b1. Tangent vectors in a face are
///    complex numbers in that basis (Z_t = X_t + iY_t, thesis 3.1); J (90° rotation) is multiplication by i.
class Mesh {
 public:
  Mesh() = default;

  /// Builds a mesh from triangle arrays. \throw TopologyError listing every problem if invalid.
  /// V  #V by 3 positions; F  #F by 3 0-based vertex indices.
  static Mesh from_triangles(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

  // ---- sizes
  int num_vertices() const { return static_cast<int>(V_.rows()); }  ///< \pre none
  int num_edges() const { return static_cast<int>(E_.rows()); }  ///< \pre none
  int num_faces() const { return static_cast<int>(F_.rows()); }  ///< \pre none

  // ---- combinatorics
  const Eigen::MatrixX3d& V() const { return V_; }    ///< #V by 3 \pre none
  const Eigen::MatrixX3i& F() const { return F_; }    ///< #F by 3 \pre none
  const Eigen::MatrixX2i& E() const { return E_; }    ///< #E by 2, E(e,0) < E(e,1) \pre none
  const Eigen::MatrixX3i& FE() const { return FE_; }  ///< #F by 3, edge opposite corner k \pre none
  const Eigen::MatrixX3i& FE_sign() const { return FE_sign_; }  ///< #F by 3, ±1 \pre none
  const Eigen::MatrixX2i& EF() const { return EF_; }  ///< #E by 2, positive / negative face or -1 \pre none
  /// #E by 2: the corner index (0..2) of edge e opposite to it in EF(e,0) / EF(e,1), or -1. \pre none
  const Eigen::MatrixX2i& EF_corner() const { return EF_corner_; }

  bool is_boundary_edge(int e) const { return EF_(e, 0) < 0 || EF_(e, 1) < 0; }  ///< \pre 0 <= e < #E
  /// A face of edge e: its positive face, else (on the boundary) its negative one. \pre 0 <= e < #E
  int face_of_edge(int e) const { return EF_(e, 0) >= 0 ? EF_(e, 0) : EF_(e, 1); }
  /// The boundary edges, ascending. \pre none
  std::vector<int> boundary_edges() const;
  /// #edges by 2: the end vertices of the listed edges, in that order (segments for mesh/segment_grid.h).
  /// \pre every listed edge is an edge of the mesh.
  Eigen::MatrixX2i edge_endpoints(const std::vector<int>& edges) const;
  bool is_boundary_vertex(int v) const { return boundary_vertex_[v] != 0; }  ///< \pre 0 <= v < #V
  /// The corner (0..2) of face f at vertex v, or -1 if v is not a vertex of f. \pre 0 <= f < #F
  int corner_of(int f, int v) const {
    for (int c = 0; c < 3; ++c)
      if (F_(f, c) == v) return c;
    return -1;
  }
  /// The face across face edge k of f, or -1 on the boundary. \pre 0 <= f < #F, 0 <= k < 3
  int neighbor(int f, int k) const {
    const int e = FE_(f, k);
    return EF_(e, 0) == f ? EF_(e, 1) : EF_(e, 0);
  }

  /// Ordered fan of vertex v: (face, corner) pairs counter-clockwise around the normal; for a boundary vertex the
  /// fan starts at the face whose clockwise side is the boundary.
  struct FanCorner {
    int face, corner;
  };
  /// \pre 0 <= v < #V
  std::span<const FanCorner> fan(int v) const {
    return {fan_.data() + fan_offsets_[v], fan_.data() + fan_offsets_[v + 1]};
  }
  int valence(int v) const;  ///< number of incident edges \pre 0 <= v < #V

  /// Boundary loops as vertex sequences, each oriented with the surface to its left. \pre none
  const std::vector<std::vector<int>>& boundary_loops() const { return boundary_loops_; }
  /// Per loop, the boundary edges in loop order (edge i joins vertex i and i+1 of the loop). \pre none
  const std::vector<std::vector<int>>& boundary_loop_edges() const { return boundary_loop_edges_; }

  // ---- components and topology
  int num_components() const { return static_cast<int>(components_.size()); }  ///< \pre none
  const std::vector<ComponentInfo>& components() const { return components_; }  ///< \pre none
  const Eigen::VectorXi& face_component() const { return face_component_; }  ///< #F. \pre none
  const Eigen::VectorXi& vertex_component() const { return vertex_component_; }  ///< #V. \pre none
  int euler_characteristic() const { return num_vertices() - num_edges() + num_faces(); }  ///< \pre none
  int num_boundary_loops() const { return static_cast<int>(boundary_loops_.size()); }  ///< \pre none
  /// Sum of the component genera. \pre none
  int genus() const;

  // ---- geometry (cached)
  const Eigen::VectorXd& face_areas() const { return face_area_; }       ///< #F \pre none
  const Eigen::MatrixX3d& face_normals() const { return face_normal_; }  ///< #F by 3, unit \pre none
  const Eigen::MatrixX3d& corner_angles() const { return corner_angle_; }  ///< #F by 3, radians \pre none
  /// \pre none
  const Eigen::MatrixX3d& corner_cotangents() const { return corner_cot_; }  ///< #F by 3, cot of corner angles
  const Eigen::VectorXd& edge_lengths() const { return edge_length_; }  ///< #E \pre none
  /// Angle defect (Def. 1.8): 2π - Σα at interior vertices, π - Σα (geodesic curvature) at boundary vertices,
  /// so that Σ_v angle_defect = 2πχ (discrete Gauss-Bonnet) holds for every mesh. \pre none
  const Eigen::VectorXd& angle_defect() const { return angle_defect_; }
  /// Face tangent basis: #F by 3 each; b1 = unit(p1 - p0), b2 = n × b1. \pre none
  const Eigen::MatrixX3d& face_basis1() const { return face_b1_; }
  const Eigen::MatrixX3d& face_basis2() const { return face_b2_; }  ///< \pre none
  /// Corner positions in the face basis: #F by 3 complex, corner 0 at the origin, corner 1 on the positive real axis.
  /// \pre none
  const Eigen::MatrixX3cd& corner_local() const { return corner_local_; }
  /// Face edge k (from corner k+1 to corner k+2) as a complex vector in the face basis. \pre 0 <= f < #F, 0 <= k < 3
  Complex edge_vector_local(int f, int k) const {
    return corner_local_(f, (k + 2) % 3) - corner_local_(f, (k + 1) % 3);
  }
  /// Levi-Civita transport across interior edge e: a tangent vector w in the basis of s = EF(e,0) is ρ_e·w in the
  /// basis of t = EF(e,1) after unfolding the two triangles into a plane. |ρ_e| = 1; 1 on boundary edges. \pre none
  const Eigen::VectorXcd& edge_transport() const { return edge_transport_; }
  double mean_edge_length() const { return mean_edge_length_; }  ///< \pre none
  double bounding_box_diagonal() const;  ///< 0 for an empty mesh. \pre none
  double total_area() const { return total_area_; }  ///< Σ face_areas(), cached \pre none

  /// Converts a 3D vector (projected to the tangent plane) into face f's complex coordinates and back. \pre 0 <= f < #F
  Complex to_local(int f, const Eigen::Vector3d& w) const {
    return {w.dot(face_b1_.row(f)), w.dot(face_b2_.row(f))};
  }
  /// \pre 0 <= f < #F
  Eigen::Vector3d to_world(int f, Complex z) const {
    return z.real() * face_b1_.row(f).transpose() + z.imag() * face_b2_.row(f).transpose();
  }

 private:
  friend struct MeshBuilder;
  void build_connectivity();
  void build_geometry();

  Eigen::MatrixX3d V_;
  Eigen::MatrixX3i F_;
  Eigen::MatrixX2i E_;
  Eigen::MatrixX3i FE_, FE_sign_;
  Eigen::MatrixX2i EF_, EF_corner_;
  std::vector<char> boundary_vertex_;
  std::vector<int> fan_offsets_;
  std::vector<FanCorner> fan_;
  std::vector<std::vector<int>> boundary_loops_, boundary_loop_edges_;
  std::vector<ComponentInfo> components_;
  Eigen::VectorXi face_component_, vertex_component_;

  Eigen::VectorXd face_area_, edge_length_, angle_defect_;
  Eigen::MatrixX3d face_normal_, corner_angle_, corner_cot_, face_b1_, face_b2_;
  Eigen::MatrixX3cd corner_local_;
  Eigen::VectorXcd edge_transport_;
  double mean_edge_length_ = 0;
  double total_area_ = 0;
};

/// The result of building a mesh from a file's soup.
struct MeshBuildResult {
  Mesh mesh;
  ValidationReport report;       ///< warnings (unreferenced vertices, flipped faces); fatal problems throw instead
  std::vector<int> vertex_map;   ///< soup vertex -> mesh vertex, -1 for dropped unreferenced vertices
  std::vector<int> face_source;  ///< mesh face -> soup face (several when polygons were triangulated)
};

/// Checks the soup against Def. 1.2 and everything else listed in ProblemKind.
/// \pre none. Does not throw: every problem is in the report.
ValidationReport validate(const PolygonSoup& soup, const ValidationOptions& options = {});

/// Validates and builds. \throw TopologyError whose problems() lists every fatal problem with its location.
MeshBuildResult build_mesh(const PolygonSoup& soup, const ValidationOptions& options = {});

}  // namespace quadcover
