// How registers are spelled (§2.2, §1.6): the one table the assembler's lexer, the disassembler and
// every register name outside a program (command lines, metadata, CSV headers) read.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

#include "vm/core/program.h"

namespace vs11 {

// A "numbered" spelling is followed by a decimal number (r7, oT3); a fixed one names a single register
// (oPos). Names are matched case-insensitively and printed as written here.
struct RegisterSpelling {
  std::string_view name;
  RegisterFile file;
  int fixed_index;  // kNumbered, or the register number the name stands for
  static constexpr int kNumbered = -1;
};
inline constexpr std::array kRegisterSpellings = {
    RegisterSpelling{"oPos", RegisterFile::kRasterOut, kRasterOutPosition},
    RegisterSpelling{"oFog", RegisterFile::kRasterOut, kRasterOutFog},
    RegisterSpelling{"oPts", RegisterFile::kRasterOut, kRasterOutPointSize},
    RegisterSpelling{"oD", RegisterFile::kAttributeOut, RegisterSpelling::kNumbered},
    RegisterSpelling{"oT", RegisterFile::kTexCoordOut, RegisterSpelling::kNumbered},
    RegisterSpelling{"r", RegisterFile::kTemp, RegisterSpelling::kNumbered},
    RegisterSpelling{"v", RegisterFile::kInput, RegisterSpelling::kNumbered},
    RegisterSpelling{"c", RegisterFile::kConst, RegisterSpelling::kNumbered},
    RegisterSpelling{"a", RegisterFile::kAddress, RegisterSpelling::kNumbered},
    // vs_2_0 on (vm/core/shader_model.h): spelled so that a vs_1_1 program naming them is told so.
    RegisterSpelling{"i", RegisterFile::kConstInt, RegisterSpelling::kNumbered},
    RegisterSpelling{"b", RegisterFile::kConstBool, RegisterSpelling::kNumbered},
    RegisterSpelling{"aL", RegisterFile::kLoop, 0},
    RegisterSpelling{"p", RegisterFile::kPredicate, RegisterSpelling::kNumbered},
    RegisterSpelling{"s", RegisterFile::kSampler, RegisterSpelling::kNumbered},
    RegisterSpelling{"l", RegisterFile::kLabel, RegisterSpelling::kNumbered},
    // vs_3_0's name for the output file (the assembler takes it only there; RegisterName(..., model)).
    RegisterSpelling{"o", RegisterFile::kTexCoordOut, RegisterSpelling::kNumbered},
};
inline constexpr std::string_view kVs30OutputSpelling = "o";

// The length of `file`'s numbered spelling ("v", "c", "oT") when `text` begins with it in any case;
// 0 otherwise.
std::size_t NumberedRegisterPrefix(std::string_view text, RegisterFile file);

// "v3" -> 3 for RegisterFile::kInput, "C12" -> 12 for kConst: the file's spelling in any case, then a
// non-negative decimal number and nothing else (no sign, no spaces). No range check: each caller
// states its own range in its message.
std::optional<int> ParseNumberedRegister(std::string_view name, RegisterFile file);

// A register named outside a program (a command line's v#=..., a metadata line, a dictionary key):
// white space around it ignored, then ParseNumberedRegister's spelling. Every such name is read by
// one of these two, so every entry point accepts the same spellings.
// "v3" -> 3, v0..v15 only.
std::optional<int> ParseInputRegister(std::string_view name);
// "c7" or "c[7]" (spaces allowed inside the brackets) -> 7, c0..c[kMaxConstantIndex].
std::optional<int> ParseConstantRegister(std::string_view name);

}  // namespace vs11
