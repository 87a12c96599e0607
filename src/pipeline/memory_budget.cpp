#include "pipeline/memory_budget.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "common/errors.h"

namespace quadcover {

double requested_quads(const Mesh& mesh, const ParamOptions& options) {
  if (options.density.target_quads > 0) return options.density.target_quads;
  const double h =
      options.density.edge_length > 0 ? options.density.edge_length : options.density.default_edge_factor * mesh.mean_edge_length();
  return h > 0 ? mesh.total_area() / (h * h) : 0;
}

std::int64_t available_bytes(std::int64_t limit_bytes) {
  if (limit_bytes > 0) return limit_bytes;
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::int64_t kb = 0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024;
  return 0;
}

bool fits_memory_budget(const Mesh& mesh, double quads, std::int64_t available) {
  return available <= 0 ||
         kBytesPerInputFace * mesh.num_faces() + kBytesPerQuad * quads <= static_cast<double>(available);
}

void check_memory_budget(const Mesh& mesh, const ParamOptions& options, std::int64_t available) {
  const double quads = requested_quads(mesh, options);
  if (fits_memory_budget(mesh, quads, available)) return;
  const double faces_bytes = kBytesPerInputFace * mesh.num_faces();
  const double need = faces_bytes + kBytesPerQuad * quads;
  const double fits = std::max(0.0, (static_cast<double>(available) - faces_bytes) / kBytesPerQuad);
  const double h = fits > 0 ? std::sqrt(mesh.total_area() / fits) : 0;
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "the density asks for about %.3g quads, which needs about %.1f GB, but %.1f GB are available; the "
                "largest that fits is about %.0f quads (an edge length of at least %.3g)",
                quads, need / 1e9, static_cast<double>(available) / 1e9, std::floor(fits), h);
  throw InputError("density", 0, msg);
}

}  // namespace quadcover
