// libFuzzer target: arbitrary bytes as .vso bytecode through the loader, validator and disassembler.
// A stream that decodes must encode back to itself, and its listing must assemble (without
// validation) to the same instructions, but for NaN payloads, which text cannot carry.
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>

#include "vm/assembler.h"
#include "vm/bytecode.h"
#include "vm/disassembler.h"
#include "vm/validator.h"

namespace {

// The disassembler prints every NaN as nan / -nan, which reads back as the canonical quiet NaN.
void CanonicalizeNans(std::vector<vs11::Instruction>& instructions) {
  constexpr std::uint32_t kSignBit = 0x80000000u, kQuietNan = 0x7FC00000u;
  for (vs11::Instruction& instruction : instructions) {
    for (std::uint32_t& bits : instruction.def_bits) {
      if (std::isnan(std::bit_cast<float>(bits))) bits = (bits & kSignBit) | kQuietNan;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::optional<std::vector<std::uint32_t>> words = vs11::WordsFromBytes(std::span(data, size));
  if (!words) return 0;
  vs11::DecodeResult decoded = vs11::Decode(*words);
  (void)decoded.diagnostics.ToString();
  if (!decoded.program) return 0;

  vs11::ValidatorOptions validator;
  validator.require_position = (size % 8) == 0;
  (void)vs11::Validate(*decoded.program, validator).ToString();

  std::string listing = vs11::Disassemble(*decoded.program);
  vs11::AssembleOptions options;
  options.validate = false;
  vs11::AssembleResult reassembled = vs11::AssembleSource(
      listing, "listing.vsh", options, [](const std::filesystem::path&) { return std::optional<std::string>(); });
  if (!reassembled.program) std::abort();  // the disassembler printed something the assembler refuses
  std::vector<vs11::Instruction> expected = decoded.program->instructions;
  CanonicalizeNans(expected);
  if (reassembled.program->instructions != expected) std::abort();
  return 0;
}
