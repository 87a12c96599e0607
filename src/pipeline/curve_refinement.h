#pragma once
// Refinement for the curve constraints (issue 14 item 3, beyond the thesis). With boundary and feature curves on
// integer iso-lines (param/alignment.h), a triangle whose three corners lie on curves can be held at zero area by
// the constraints alone: a boundary ear (two boundary edges) or a triangle between two vertices of one crease and a
// third on it has its three corners on one iso-line whatever the map does, so no injective map exists in the
// subspace (param/untangle.h reports such faces as stuck). Splitting one of its edges that is not a curve edge puts
// an unconstrained vertex into each part, and the map can give both parts positive area.
#include <array>
#include <memory>
#include <vector>

#include "field/feature_alignment.h"
#include "mesh/mesh.h"

namespace quadcover {

/// The interior edges to split: for every face whose three corners are curve vertices (on a boundary edge when
/// features.boundaries, or on a sharp feature edge of feature_constraints) and that has an edge that is not a curve
/// edge, its longest such edge (ties: lower edge index), unless one of its edges is chosen already. Ascending.
/// \pre none
std::vector<int> curve_refinement_edges(const Mesh& mesh, const FeatureOptions& features);

/// A mesh refined by curve_refinement_edges, or none when nothing needs it.
struct CurveRefinement {
  std::shared_ptr<const Mesh> mesh;     ///< null when the input is used as it is
  std::vector<std::array<int, 2>> split;  ///< input vertex pairs of the split edges; new vertex #V + k is the midpoint of split[k]
  int added_faces = 0;
};

/// \pre mesh is a valid triangle mesh. Deterministic; the refined mesh has the input's vertices first.
CurveRefinement refine_for_curves(const Mesh& mesh, const FeatureOptions& features);

}  // namespace quadcover
