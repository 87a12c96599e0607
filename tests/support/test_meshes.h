#pragma once
// Test helpers: meshes shipped in tests/data and meshes generated in the test.
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace quadcover::testing {

/// Path of tests/data/NAME (NAME without extension gets ".obj").
std::string data_path(const std::string& name);
/// Loads and builds tests/data/NAME.obj.
Mesh load_test_mesh(const std::string& name);

/// A closed torus with radii R > r, n_major × n_minor quads split into triangles.
Mesh make_torus(int n_major, int n_minor, double R = 2.0, double r = 0.7);
/// A regular triangulated grid of the unit square [0,1]² (z = 0), n × n quads.
Mesh make_grid(int n);
/// The triangles of make_grid(n) without the quads (i, j) with i and j odd and below n − 2: ((n − 2) / 2)²
/// separate square holes, as faces over the vertices grid.V() of grid = make_grid(n).
Eigen::MatrixX3i grid_faces_with_holes(const Mesh& grid, int n);
/// An open cylinder of radius r and height h around the z axis, n_around × n_up quads.
Mesh make_cylinder(int n_around, int n_up, double r = 1.0, double h = 2.0);
/// A square plate [−side/2, side/2]² × [0, thickness] drilled through its centre by a hole of radius r (genus 1), as
/// CAD exports triangulate it: top and bottom are one strip of 2·n_around triangles from the square to the hole's
/// n-gon (n_around a multiple of 8: the square's corners are among the angles), walls of one row of quads. Every
/// edge of the square and both rims are 90° creases; each rim is a closed crease loop.
Mesh make_drilled_plate(int n_around, double r, double side = 2.0, double thickness = 0.5);
/// A spur gear as a coarse CAD export: a prism of `thickness` over an outline of `teeth` teeth (8 outline vertices a
/// tooth: 4 on the top at radius 1, 4 at the root at radius 0.8), each cap a fan around its centre, the wall one row
/// of quads. Both outlines and the wall edges at the tooth corners are 90° creases, on chains of at most 3 edges
/// that turn by 90° at every corner; every other edge bends by 3.75° (the arcs) or not at all.
Mesh make_gear(int teeth, double thickness = 0.3);
/// Two components in one mesh: make_torus(12, 8) and, after its vertices, make_cylinder(10, 4).
Mesh make_torus_and_cylinder();
/// Copies of `mesh` side by side, one per scale: copy c scaled by scales[c] and moved along x by c times 1.5 widths
/// of `mesh`, so that no two overlap (components of very different sizes when the scales differ).
Mesh scaled_copies(const Mesh& mesh, const std::vector<double>& scales);
/// A UV sphere-like closed surface (octahedron subdivided `level` times and projected), scaled by (a, b, c).
Mesh make_ellipsoid(int level, double a = 1.0, double b = 1.0, double c = 1.0);
/// A fan of n triangles around one apex (0,0,height) over the unit circle in z = 0 (a disk, apex = vertex 0, rim =
/// vertices 1..n), or with closed = true also a second fan to the apex (0,0,-height) (a bipyramid, apex n+1):
/// vertices of valence n.
Mesh make_fan(int n, bool closed, double height = 0.3);

/// The edges of `mesh` that are not boundary edges, in edge order.
std::vector<int> interior_edges(const Mesh& mesh);

/// The same surface with every face's orientation reversed (normals flipped: a closed mesh faces inward).
Mesh with_faces_reversed(const Mesh& mesh);

}  // namespace quadcover::testing
