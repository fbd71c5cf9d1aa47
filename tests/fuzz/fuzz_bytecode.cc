// libFuzzer target: arbitrary bytes as .vso bytecode (see CheckBytecode in fuzz_properties.h).
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_properties.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (std::optional<std::string> failure = vs11::fuzz::CheckBytecode({data, size})) {
    std::fprintf(stderr, "fuzz_bytecode: %s\n", failure->c_str());
    std::abort();
  }
  return 0;
}
