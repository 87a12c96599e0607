#pragma once
// Removal of zero-area triangles from a triangle soup, for `quadcover repair`: the faces validation rejects as
// degenerate (mesh/validate.h) but that carry no surface, so the surface is the same without them.
//  - A triangle with a repeated vertex (a, a, b) is dropped.
//  - A triangle with the same vertex set as an earlier one is dropped (the first is kept).
//  - A cap, a zero-area triangle (a, b, m) with its corner m strictly inside the opposite edge a–b: with a triangle
//    (b, a, n) across that edge, the edge is flipped to m–n, giving (a, n, m) and (n, b, m), which tile (b, a, n)
//    exactly; on the boundary (no triangle across) the cap is dropped and the boundary runs through m.
//  - A needle, a zero-area triangle with two corners a, b at one point (up to round-off): b is merged into a (the
//    triangles on the edge a–b go, the others at b take a), where a and b have no common neighbour but the third
//    corners of those triangles and the merge does not pinch two boundary stretches together.
// Caps whose flip would make a degenerate triangle or an edge that exists already, and needles whose merge would
// break the surface, are left for validation to report. Vertex positions never change (a merged b is left
// unused).
#include <cstddef>

#include "io/polygon_soup.h"

namespace quadcover {

struct DegenerateFaceRemoval {
  std::size_t repeated_vertex = 0;  ///< triangles with a repeated vertex, dropped
  std::size_t duplicates = 0;       ///< triangles repeating an earlier one's vertex set, dropped
  std::size_t flipped_caps = 0;     ///< caps whose long edge was flipped with the triangle across it
  std::size_t boundary_caps = 0;    ///< caps on the boundary, dropped
  std::size_t merged_needles = 0;   ///< needles whose two corners at one point were merged
  /// \pre none
  std::size_t total() const { return repeated_vertex + duplicates + flipped_caps + boundary_caps + merged_needles; }
};

/// Applies the removals above to the triangles of `soup` (faces of other sizes and faces with indices out of range
/// are kept as they are for validation); zero area means 2·area <= tolerance · (longest edge)², as in validation.
/// Faces keep their file lines (a flipped pair takes the lines of the cap and its neighbour); per-corner texture
/// indices are dropped when any face changed. \pre none
DegenerateFaceRemoval remove_degenerate_faces(PolygonSoup& soup, double tolerance);

}  // namespace quadcover
