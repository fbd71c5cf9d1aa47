#include "tests/fuzz/fuzz_properties.h"

#include <bit>
#include <cmath>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/disassembler.h"
#include "vm/asm/validator.h"

namespace vs11::fuzz {
namespace {

FileReader InMemoryReader(std::string_view input) {
  return [input](const std::filesystem::path& path) -> std::optional<std::string> {
    if (path.filename() == "self.vsh") return std::string(input);
    if (path.filename() == "empty.vsh") return std::string();
    return std::nullopt;
  };
}

// The disassembler prints every NaN as nan / -nan, which reads back as the canonical quiet NaN.
void CanonicalizeNans(std::vector<Instruction>& instructions) {
  constexpr std::uint32_t kSignBit = 0x80000000u, kQuietNan = 0x7FC00000u;
  for (Instruction& instruction : instructions) {
    for (std::uint32_t& bits : instruction.def_bits) {
      if (std::isnan(std::bit_cast<float>(bits))) bits = (bits & kSignBit) | kQuietNan;
    }
  }
}

// Assembles a listing with the validation its program passed: a valid program's listing must be a
// valid program too (a DX8 stream printed as DX9 text, say, would fail for want of dcl).
AssembleResult Reassemble(const std::string& listing, bool require_position) {
  AssembleOptions options;
  options.require_position = require_position;
  return AssembleSource(listing, "listing.vsh", options, InMemoryReader(""));
}

}  // namespace

std::optional<std::string> CheckSource(std::string_view text) {
  AssembleOptions options;
  options.require_position = (text.size() % 2) == 0;  // both the whole-shader and the fragment rules
  AssembleResult result = AssembleSource(text, "self.vsh", options, InMemoryReader(text));
  (void)result.diagnostics.ToString();
  if (!result.program) {
    if (!result.diagnostics.HasErrors()) return "refused without an error";
    return std::nullopt;
  }
  std::vector<std::uint32_t> words = Encode(*result.program);
  DecodeResult decoded = Decode(words);
  if (!decoded.program) return fmt::format("the assembler wrote a stream the decoder refuses: {}", decoded.diagnostics.ToString());
  std::string listing = Disassemble(*result.program);
  AssembleResult reassembled = Reassemble(listing, options.require_position);
  if (!reassembled.program) return fmt::format("the listing does not assemble:\n{}{}", listing, reassembled.diagnostics.ToString());
  if (Encode(*reassembled.program) != words) return fmt::format("the listing assembles to other tokens:\n{}", listing);
  return std::nullopt;
}

std::optional<std::string> CheckBytecode(std::span<const std::uint8_t> bytes) {
  std::optional<std::vector<std::uint32_t>> words = WordsFromBytes(bytes);
  if (!words) return std::nullopt;
  DecodeResult decoded = Decode(*words);
  (void)decoded.diagnostics.ToString();
  if (!decoded.program) {
    if (!decoded.diagnostics.HasErrors()) return "refused without an error";
    return std::nullopt;
  }
  ValidatorOptions validator;
  validator.require_position = (bytes.size() % 8) == 0;
  Diagnostics problems = Validate(*decoded.program, validator);
  (void)problems.ToString();
  std::string listing = Disassemble(*decoded.program);
  // An invalid program need not survive text: an empty write mask, say, prints as "r0.".
  if (problems.HasErrors()) return std::nullopt;

  AssembleResult reassembled = Reassemble(listing, validator.require_position);
  if (!reassembled.program) return fmt::format("the listing does not assemble:\n{}{}", listing, reassembled.diagnostics.ToString());
  std::vector<Instruction> expected = decoded.program->instructions;
  CanonicalizeNans(expected);
  if (reassembled.program->instructions != expected) return fmt::format("the listing assembles to other instructions:\n{}", listing);
  return std::nullopt;
}

}  // namespace vs11::fuzz
