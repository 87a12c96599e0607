// libFuzzer target for the OFF reader (plus validation and mesh construction of what it returns).
#include "fuzz_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return quadcover::fuzz::run_reader(data, size, [](std::string_view bytes, const std::string& name) {
    return quadcover::read_off_from_memory(bytes, name);
  });
}
