// libFuzzer target: arbitrary bytes as .vsh source (see CheckSource in fuzz_properties.h).
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_properties.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (std::optional<std::string> failure = vs11::fuzz::CheckSource({reinterpret_cast<const char*>(data), size})) {
    std::fprintf(stderr, "fuzz_assembler: %s\n", failure->c_str());
    std::abort();
  }
  return 0;
}
