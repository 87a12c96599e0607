#include "io/feature_edge_file.h"

#include <ostream>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "io/read_mesh.h"
#include "io/text_scanner.h"

namespace quadcover {

namespace {
constexpr long long kMaxVertex = (1LL << 31) - 1;
}  // namespace

std::vector<FeatureEdgeLine> read_feature_edges(const std::string& path) {
  return read_feature_edges_from_memory(read_file_bytes(path), path);
}

std::vector<FeatureEdgeLine> read_feature_edges_from_memory(std::string_view bytes, const std::string& name) {
  std::vector<FeatureEdgeLine> edges;
  TextScanner scan(bytes);
  while (scan.next_line()) {
    if (scan.at_line_end()) continue;
    long long a = 0, b = 0;
    if (!scan.integer(a) || !scan.integer(b) || !scan.at_line_end())
      throw InputError(name, scan.line(), "expected two vertex numbers (an edge of the mesh), counted from 1");
    if (a < 1 || b < 1)
      throw InputError(name, scan.line(), "vertex numbers count from 1, got " + std::to_string(a < 1 ? a : b));
    if (a > kMaxVertex || b > kMaxVertex)
      throw InputError(name, scan.line(), "vertex number " + std::to_string(a > kMaxVertex ? a : b) + " is too large");
    if (a == b)
      throw InputError(name, scan.line(), "an edge needs two different vertices, got " + std::to_string(a) + " twice");
    edges.push_back({static_cast<int>(a - 1), static_cast<int>(b - 1), scan.line()});
  }
  return edges;
}

void write_feature_edges(const std::string& path, const std::vector<std::pair<int, int>>& edges,
                         const std::vector<std::string>& comment) {
  write_file_atomically(path, [&](std::ostream& out) {
    for (const std::string& line : comment) out << "# " << line << '\n';
    for (const auto& [a, b] : edges) out << a + 1 << ' ' << b + 1 << '\n';
  });
}

}  // namespace quadcover
