// What the fuzz targets check, shared with the unit tests that replay the inputs they found
// (tests/vm/asm/fuzz_regression_test.cc). Each returns nullopt when the input was handled properly
// (accepted or refused with diagnostics), otherwise what went wrong. Crashes and sanitizer reports
// need no return value: they stop the process.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace vs11::fuzz {

// Source text through the preprocessor, assembler and validator. `#include "self.vsh"` reads the
// input itself (so cycles and deep nesting are reachable), "empty.vsh" is empty, anything else is
// missing. Whatever assembles must decode, and its disassembly must assemble, validation included,
// to the same tokens (the round trip vm/asm/disassembler.h promises).
std::optional<std::string> CheckSource(std::string_view text);

// Bytes as a .vso token stream through the decoder, validator and disassembler. A stream that
// decodes and validates (so the assembler could have written it) must disassemble to text that
// assembles and validates to the same instructions (NaN payloads aside: text carries only the
// canonical NaN).
std::optional<std::string> CheckBytecode(std::span<const std::uint8_t> bytes);

}  // namespace vs11::fuzz
