#pragma once
// Refusing a density the machine cannot hold, before anything is allocated: a job's peak memory grows with the
// input's faces and with the quads the density asks for (the map, the extraction and the quad mesh), so a request for
// 10^8 quads on a small mesh is an input error with the largest count that fits, not a std::bad_alloc after minutes.
#include <cstdint>

#include "mesh/mesh.h"
#include "param/parameterize.h"

namespace quadcover {

/// Bytes per input face and per requested quad, rounded up from the peaks of BENCHMARKS.md ("Stage profile": 3.8 KB
/// per face at 1M faces; extraction and quad mesh well under 1 KB per quad).
inline constexpr double kBytesPerInputFace = 4096, kBytesPerQuad = 1024;

/// The quads `options` asks for on `mesh`: N, or area / h² for an edge length h, or for the default density the
/// mesh's own resolution (area / (default_edge_factor · mean edge)²). \pre none
double requested_quads(const Mesh& mesh, const ParamOptions& options);

/// The memory available to the job: `limit_bytes` if positive, else the machine's MemAvailable (/proc/meminfo; 0 if
/// unknown, then nothing is refused). \pre none
std::int64_t available_bytes(std::int64_t limit_bytes = 0);

/// Whether a job of `quads` quads on `mesh` fits in `available` bytes (always when available ≤ 0). \pre none
bool fits_memory_budget(const Mesh& mesh, double quads, std::int64_t available);

/// \throw InputError (file "density") naming the estimate, the memory available and the largest quad count that fits,
/// if the job's estimated peak exceeds `available`. Nothing is checked when available ≤ 0.
void check_memory_budget(const Mesh& mesh, const ParamOptions& options, std::int64_t available);

}  // namespace quadcover
