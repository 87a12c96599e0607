#pragma once
// The fans of the vertices on a cut, made once per cut: complete_translations and jump_function
// (param/disk_functions.h) walk them for every translation vector, and the period matrix (6.3.2) makes one such
// vector per path, where searching the fans and sorting the vertices anew each time cost more than the walks.
#include <span>
#include <vector>

#include "param/cover_cut.h"

namespace quadcover {

struct CutFans {
  std::vector<int> vertices;  ///< the vertices with a cut edge, ascending
  /// Per entry k of vertices: its crossings (fan_crossings order) at [offset[k], offset[k + 1]).
  std::vector<int> offset;
  std::vector<FanCrossing> crossings;
  /// Entries of vertices whose parent edge in the shortest-path forest is cut, from the leaves to the roots: the
  /// order in which complete_translations fixes the parent edges' translations.
  std::vector<int> elimination;

  /// \pre 0 <= k < vertices.size()
  std::span<const FanCrossing> crossings_of(int k) const {
    return {crossings.data() + offset[k], crossings.data() + offset[k + 1]};
  }
};

/// \pre cut = build_cover_cut(mesh, …). \throw only std::bad_alloc.
CutFans cut_fans(const Mesh& mesh, const CoverCut& cut);

}  // namespace quadcover
