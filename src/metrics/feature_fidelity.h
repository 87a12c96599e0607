#pragma once
// How well a remesh keeps the input's boundary and sharp feature curves (issue 15; beyond the thesis): the input's
// feature edges are sampled densely and each sample's distance to the nearest output edge is measured in units of
// h, the output's mean edge length.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <vector>

#include "field/feature_alignment.h"
#include "mesh/mesh.h"

namespace quadcover {

struct FeatureFidelityOptions {
  /// Which edges are features: boundary edges when `boundaries`, and every interior edge whose dihedral angle exceeds
  /// sharp_angle_degrees (issue 15's definition: isolated sharp edges count, min_curve_edges = 1), whether or not
  /// the field follows it.
  FeatureOptions features{.boundaries = true, .sharp_angle_degrees = 35.0, .min_curve_edges = 1, .given = {}};
  /// The sharp edges the field follows (field/feature_alignment.h with these options: the job passes its own), also
  /// measured on their own (FeatureFidelity::followed).
  FeatureOptions followed;
  double spacing = 0.05;        ///< sample spacing along the feature edges, in h
  double covered_within = 0.1;  ///< a sample is covered when an output edge is this close, in h
};

/// Distances of one set of samples to the output edges, in h.
struct FeatureFidelityPart {
  int edges = 0;  ///< input feature edges sampled
  int samples = 0;
  double covered_percent = 0;  ///< 100 · share of samples within covered_within
  double mean = 0, p95 = 0, max = 0;
};

struct FeatureFidelity {
  double h = 0;  ///< output mean edge length (undirected edges)
  FeatureFidelityPart boundary, sharp, total;  ///< total: boundary and sharp
  FeatureFidelityPart followed;  ///< the sharp edges the field follows (FeatureFidelityOptions::followed), a subset
};

/// Samples the feature edges of `reference` (the input triangle mesh) every spacing·h and measures each sample's
/// distance to the nearest edge of the polygon mesh (V, faces). Parallel, the same result for any thread count.
/// \throw InputError if the polygon mesh has no edge of positive length or a face index out of range.
FeatureFidelity feature_fidelity(const Mesh& reference, const Eigen::MatrixX3d& V,
                                 const std::vector<std::vector<int>>& faces,
                                 const FeatureFidelityOptions& options = {});

/// {"h", "boundary", "sharp", "followed", "total"}; each part {"edges", "samples", "covered_percent", "mean", "p95",
/// "max"} (covered_percent and the distances null for a part without samples). \pre none
nlohmann::json feature_fidelity_to_json(const FeatureFidelity& f);

}  // namespace quadcover
