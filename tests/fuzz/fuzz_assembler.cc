// libFuzzer target: arbitrary bytes as .vsh source through the preprocessor, assembler and validator.
// Whatever assembles must survive the round trip the disassembler promises (vm/disassembler.h):
// Disassemble, reassemble, and the token stream is the same.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "vm/assembler.h"
#include "vm/bytecode.h"
#include "vm/disassembler.h"

namespace {

// `#include "self.vsh"` reads the input itself (so cycles and deep nesting are reachable) and
// `#include "empty.vsh"` an empty file; every other name is missing.
vs11::FileReader InMemoryReader(std::string_view input) {
  return [input](const std::filesystem::path& path) -> std::optional<std::string> {
    if (path.filename() == "self.vsh") return std::string(input);
    if (path.filename() == "empty.vsh") return std::string();
    return std::nullopt;
  };
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  vs11::AssembleOptions options;
  options.require_position = (size % 2) == 0;  // both the whole-shader and the fragment rules
  vs11::AssembleResult result = vs11::AssembleSource(text, "self.vsh", options, InMemoryReader(text));
  (void)result.diagnostics.ToString();
  if (!result.program) return 0;

  std::vector<std::uint32_t> words = vs11::Encode(*result.program);
  vs11::DecodeResult decoded = vs11::Decode(words);
  if (!decoded.program) std::abort();  // the assembler wrote a stream its own decoder refuses

  vs11::AssembleOptions again;
  again.validate = false;
  std::string listing = vs11::Disassemble(*result.program);
  vs11::AssembleResult reassembled = vs11::AssembleSource(listing, "listing.vsh", again, InMemoryReader(""));
  if (!reassembled.program || vs11::Encode(*reassembled.program) != words) std::abort();
  return 0;
}
