#pragma once
// Input validation (thesis Def. 1.2: an abstract simplicial surface). Every defect is reported with the
// offending face/vertex indices and their file locations; nothing is dropped silently.
#include <string>
#include <vector>

#include "io/polygon_soup.h"

namespace quadcover {

enum class ProblemKind {
  Empty,                    ///< no vertices or no faces
  NonFiniteCoordinate,      ///< NaN or inf in a position
  IndexOutOfRange,          ///< a face refers to a vertex that does not exist
  NotTriangle,              ///< polygon with more than 3 corners (allowed with `triangulate`)
  RepeatedVertex,           ///< a face uses the same vertex twice
  DegenerateFace,           ///< zero-area triangle (collinear corners)
  DuplicateFace,            ///< two faces with the same vertex set
  NonManifoldEdge,          ///< an edge with more than two faces
  NonManifoldVertex,        ///< the faces at a vertex form more than one fan
  InconsistentOrientation,  ///< orientable, but neighbouring faces disagree (fixable with `fix_orientation`)
  NonOrientable,            ///< no consistent orientation exists (Möbius band, Klein bottle)
  UnreferencedVertex,       ///< a vertex no face uses: a warning; such vertices are dropped and counted
};

const char* to_string(ProblemKind kind);  ///< \pre none

struct MeshProblem {
  ProblemKind kind;
  bool fatal = true;          ///< false for warnings (unreferenced vertices)
  std::string message;        ///< one line naming the problem and where (file:line, indices)
  std::vector<long> faces;    ///< 0-based indices into the soup's faces
  std::vector<long> vertices; ///< 0-based indices into the soup's vertices
};

struct ValidationOptions {
  bool triangulate = false;       ///< fan-triangulate polygons instead of rejecting them
  bool fix_orientation = false;   ///< flip faces of an orientable but inconsistently oriented input
  /// A triangle is degenerate when 2·area <= degenerate_tolerance · (longest edge)² (collinear to round-off).
  double degenerate_tolerance = 1e-12;
  std::size_t max_listed = 20;    ///< how many located elements one message lists before "... and N more"
};

struct ValidationReport {
  std::vector<MeshProblem> problems;
  std::size_t unreferenced_vertices = 0;
  std::size_t flipped_faces = 0;  ///< faces flipped by fix_orientation
  /// \pre none
  bool valid() const {
    for (const auto& p : problems)
      if (p.fatal) return false;
    return true;
  }
  /// \pre none
  bool has(ProblemKind kind) const {
    for (const auto& p : problems)
      if (p.kind == kind) return true;
    return false;
  }
};

}  // namespace quadcover
