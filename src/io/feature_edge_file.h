#pragma once
// Feature edge files (`--features FILE` reads one, `field --save-features FILE` writes one): a text file with one
// edge per line, two vertex numbers counted from 1 in the order of the mesh file's vertices (OBJ's own numbering,
// for every mesh format); `#` starts a comment, blank lines are skipped.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace quadcover {

/// One edge of a feature file: its two vertex numbers (0-based here) and the line it was on.
struct FeatureEdgeLine {
  int a = 0, b = 0;
  long line = 0;
};

/// \throw InputError (file, line) if the file cannot be read, a line does not hold exactly two integers, or a
/// number is below 1 or names the same vertex twice.
std::vector<FeatureEdgeLine> read_feature_edges(const std::string& path);
/// \throw InputError (name, line) as read_feature_edges.
std::vector<FeatureEdgeLine> read_feature_edges_from_memory(std::string_view bytes, const std::string& name);

/// Writes `edges` (0-based vertex pairs of the mesh file) in this format, atomically, after the comment lines
/// `comment` (each prefixed with "# "). \throw InputError (naming `path`) if it cannot be written.
void write_feature_edges(const std::string& path, const std::vector<std::pair<int, int>>& edges,
                         const std::vector<std::string>& comment);

}  // namespace quadcover
