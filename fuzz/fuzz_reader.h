#pragma once
// Shared body of the reader fuzz targets: parse the bytes, then validate the soup and build the mesh when it is
// valid. The only acceptable outcomes are a result or a typed quadcover error; anything else (crash, hang,
// sanitizer report, unbounded allocation, std::bad_alloc) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "common/errors.h"
#include "io/read_mesh.h"
#include "mesh/mesh.h"

namespace quadcover::fuzz {

template <class Reader>
int run_reader(const std::uint8_t* data, std::size_t size, Reader&& read) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const PolygonSoup soup = read(bytes, std::string("fuzz-input"));
    ValidationOptions options;
    options.triangulate = true;  // exercise the polygon path too
    options.fix_orientation = true;
    const ValidationReport report = validate(soup, options);
    if (report.valid()) (void)build_mesh(soup, options);
  } catch (const InputError&) {
  } catch (const TopologyError&) {
  }
  return 0;
}

}  // namespace quadcover::fuzz
