#pragma once
// Refinement for cones (issue 14 item 3, beyond the thesis). The field's singularities of index ±1/2 or more are
// split into quarter cones on nearby interior vertices of index 0 (field/singularity_split.h). A triangulation too
// coarse to have such vertices (a disk fanned around its one interior vertex, a few triangles around a high-valence
// apex) keeps the whole singularity. From ±3/4 on that costs validity or a vertex of the quad mesh: +3/4 is a
// valence-1 spike, +1 a cone of angle 0 (the map folds flat), −3/4 and beyond a vertex of valence 7 or more.
// Splitting the edges at such a vertex at their midpoints gives it new interior neighbours, and the field is made
// again (pipeline/parameterize_mesh.cpp field_on_refined_mesh).
#include <vector>

#include "field/frame_field.h"
#include "mesh/mesh.h"
#include "pipeline/curve_refinement.h"

namespace quadcover {

/// The interior vertices whose cross-field quarter index is at least min_quarters in absolute value, ascending.
/// \pre field was made on mesh; min_quarters >= 1.
std::vector<int> unsplit_singularities(const Mesh& mesh, const FrameField& field, int min_quarters);

/// Splits every edge at the listed vertices of `mesh` at its midpoint (mesh/split_edges.h) and records it in
/// `refinement`: its mesh becomes the refined one, the split vertex pairs (numbers of `mesh`) and the added faces are
/// appended. Nothing when `vertices` is empty. \pre mesh is refinement's mesh (or the input when it has none); the
/// vertices are vertices of mesh.
void refine_around_vertices(const Mesh& mesh, const std::vector<int>& vertices, CurveRefinement& refinement);

}  // namespace quadcover
