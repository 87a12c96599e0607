#pragma once
// Display meshes small enough for an HTML page: vertex clustering on a uniform grid (each occupied cell becomes one
// vertex at the mean of its vertices; faces whose corners fall in fewer than 3 cells vanish, faces landing on the
// same cells are kept once). Seams and branch points move to their cells. Only the picture is reduced: every number
// of the report is of the full mesh.
#include <cstddef>

#include "render/html_report.h"

namespace quadcover {

/// `mesh` with at most max_faces faces (unchanged if it has no more). The cell is grown by 25 % from
/// sqrt(area / max_faces) until the face count fits. Per-corner uv stay those of the surviving corners (the
/// checkerboard is exact on faces much larger than a cell and approximate elsewhere); polygons keep their corner
/// order with repeated cells removed. Sets decimated_from (the original face count) and cell_size.
/// \pre face indices in [0, #V); seams and branch point vertices too; max_faces > 0.
HtmlMesh decimate_display_mesh(const HtmlMesh& mesh, std::size_t max_faces);

}  // namespace quadcover
