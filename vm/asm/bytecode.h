// D3D9 shader bytecode for vs_1_1 (§4): the only place that knows the token bit layout.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vm/core/diagnostic.h"
#include "vm/core/program.h"

namespace vs11 {

inline constexpr std::uint32_t kEndToken = 0x0000FFFF;
inline constexpr std::uint16_t kCommentOpcode = 0xFFFE;
inline constexpr std::uint32_t kMaxCommentWords = 0x7FFF;

// The token stream Microsoft's assembler writes for `program`: version, instructions (comments where
// they stood), end token.
std::vector<std::uint32_t> Encode(const Program& program);

struct DecodeResult {
  std::optional<Program> program;  // set when the stream is well formed
  Diagnostics diagnostics;         // each error carries the word offset of the bad token
};
// Reads a token stream, checking the structure of §4.12 (version, reserved bits, known vs_1_1 opcodes,
// complete instructions, end token last). Never reads past `words`. The program's word_offsets say
// where each instruction starts, so that the validator can point at the bad word.
DecodeResult Decode(std::span<const std::uint32_t> words);

// Little-endian bytes <-> 32-bit words. A byte count that is not a multiple of 4 is an error.
std::optional<std::vector<std::uint32_t>> WordsFromBytes(std::span<const std::uint8_t> bytes);
std::vector<std::uint8_t> BytesFromWords(std::span<const std::uint32_t> words);

}  // namespace vs11
