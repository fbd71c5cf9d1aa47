#include "vm/asm/disassembler.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "vm/asm/lexer.h"

namespace vs11 {
namespace {

std::string VersionLine(std::uint32_t version, Syntax syntax) {
  auto spelling = std::find_if(kVersionSpellings.begin(), kVersionSpellings.end(), [&](const VersionSpelling& v) {
    return v.token == version && v.dx9 == (syntax == Syntax::kDx9);
  });
  if (spelling != kVersionSpellings.end()) return std::string(spelling->text);
  // Only for hand-built programs; Decode rejects other versions.
  return fmt::format("{} ; unknown version token 0x{:08X}", kVersionSpellings.front().text, version);
}

// DX9: c3[a0.x] (Microsoft's disassembler); DX8: c[a0.x + 3], as the DX8 documentation writes it.
// (Only constants can be relative; any other relative register, which the validator refuses, keeps the
// DX9 form so that it is printed as what it is.)
std::string SwizzleText(Swizzle swizzle);

// vs_1_1: a0.x. Later models: a0 with its swizzle (none for .xyzw), or aL.
std::string AddressText(const AddressRegister& address, ShaderModel model) {
  if (model == ShaderModel::kVs11) return fmt::format("{}.{}", kAddressRegisterName, kLaneLetters[kAddressLane]);
  if (address.file == RegisterFile::kLoop) return RegisterName(RegisterFile::kLoop, 0);
  return std::string(kAddressRegisterName) + SwizzleText(Swizzle(address.swizzle_bits));
}

std::string RegisterText(const RegisterRef& reg, Syntax syntax, ShaderModel model) {
  const std::string address = AddressText(reg.address, model);
  if (reg.relative && reg.file == RegisterFile::kConst && syntax == Syntax::kDx8) {
    return reg.index == 0 ? fmt::format("c[{}]", address) : fmt::format("c[{} + {}]", address, reg.index);
  }
  std::string text = RegisterName(reg.file, reg.index, model);
  if (reg.relative) text += fmt::format("[{}]", address);
  return text;
}

// Omitted only when full and the assembler's default: `m3x3 r0.xyzw` keeps its mask, so that it does
// not come back as the default .xyz.
std::string MaskText(WriteMask mask, WriteMask default_mask = WriteMask()) {
  if (mask.is_full() && default_mask.is_full()) return "";
  std::string text = ".";
  for (int lane = 0; lane < 4; ++lane) {
    if (mask.has(lane)) text += kLaneLetters[lane];
  }
  return text;
}

std::string SwizzleText(Swizzle swizzle) {
  if (swizzle.is_identity()) return "";
  std::string text = ".";
  int letters = swizzle.is_replicate() ? 1 : 4;
  for (int lane = 0; lane < letters; ++lane) text += kLaneLetters[swizzle[lane]];
  return text;
}

std::string MnemonicText(const Instruction& instruction) {
  if (TakesComparison(instruction.opcode)) {
    const int comparison = instruction.comparison;
    return fmt::format("{}_{}", ComparisonStem(instruction.opcode),
                       comparison > 0 && comparison < static_cast<int>(kComparisonNames.size())
                           ? std::string(kComparisonNames[comparison])
                           : fmt::format("comparison{}", comparison));  // hand-built programs only
  }
  std::string text(instruction.info().mnemonic);
  if (instruction.dest.saturate) text += "_sat";
  if (instruction.opcode != Opcode::kDcl) return text;
  text += '_';
  if (instruction.dest.reg.file == RegisterFile::kSampler) {
    const int type = instruction.sampler_type;
    return text + (type >= 0 && type < static_cast<int>(kSamplerTypeNames.size()) && !kSamplerTypeNames[type].empty()
                       ? std::string(kSamplerTypeNames[type])
                       : fmt::format("sampler{}", type));  // hand-built programs only; Decode rejects these
  }
  if (instruction.usage >= 0 && instruction.usage < static_cast<int>(kDeclUsageNames.size())) {
    text += kDeclUsageNames[instruction.usage];
  } else {
    text += fmt::format("usage{}", instruction.usage);  // hand-built programs only; Decode rejects these
  }
  if (instruction.usage_index != 0) text += fmt::format("{}", instruction.usage_index);
  return text;
}

// Shortest text that reads back as the same float; nan/inf spelled as the assembler reads them.
std::string FloatText(std::uint32_t bits) {
  float value = std::bit_cast<float>(bits);
  if (std::isnan(value)) return (bits & kFloatSignBit) ? "-nan" : "nan";
  if (std::isinf(value)) return value < 0 ? "-inf" : "inf";
  return fmt::format("{}", value);
}

// A `;` note for def values the text cannot carry exactly (NaN payloads), or "".
std::string DefNote(const Instruction& instruction) {
  std::string note;
  for (int i = 0; i < 4; ++i) {
    std::uint32_t bits = instruction.def_bits[i];
    if (std::isnan(std::bit_cast<float>(bits)) && (bits & ~kFloatSignBit) != kQuietNanBits) {
      note += fmt::format("{} value {} is NaN 0x{:08X}", note.empty() ? " ;" : ",", i, bits);
    }
  }
  return note;
}

std::string CommentLine(const CommentBlock& block) {
  std::string line = fmt::format("; comment ({} words)", block.words.size());
  if (!block.words.empty()) line += ":";
  for (std::uint32_t word : block.words) line += fmt::format(" 0x{:08X}", word);
  return line;
}

}  // namespace

Syntax SyntaxOf(const Program& program) {
  if (program.model() != ShaderModel::kVs11) return Syntax::kDx9;
  const bool declares = std::any_of(program.instructions.begin(), program.instructions.end(),
                                    [](const Instruction& instruction) { return instruction.opcode == Opcode::kDcl; });
  return declares ? Syntax::kDx9 : Syntax::kDx8;
}

std::string FormatDest(const DestOperand& dest, ShaderModel model) {
  return RegisterText(dest.reg, Syntax::kDx9, model) + MaskText(dest.mask);
}

std::string FormatSource(const SourceOperand& source, Syntax syntax, ShaderModel model) {
  std::string text = source.logical_not ? "!" : source.negate ? "-" : "";
  if (source.absolute && !source.reg.relative) {
    text += RegisterName(source.reg.file, source.reg.index, model) + "_abs";
  } else {
    text += RegisterText(source.reg, syntax, model);
    if (source.absolute) text += "_abs";  // hand-built programs only: the assembler has no spelling for it
  }
  text += SwizzleText(source.swizzle);
  return text;
}

std::string FormatInstruction(const Instruction& instruction, Syntax syntax, ShaderModel model) {
  const OpcodeInfo& info = instruction.info();
  std::vector<std::string> operands;
  if (info.has_dest()) {
    operands.push_back(RegisterText(instruction.dest.reg, syntax, model) +
                       MaskText(instruction.dest.mask, WriteMask(info.default_mask)));
  }
  if (info.shape == OperandShape::kDefinition) {
    for (std::uint32_t bits : instruction.def_bits) operands.push_back(FloatText(bits));
  } else if (info.shape == OperandShape::kIntDefinition) {
    for (std::uint32_t bits : instruction.def_bits) operands.push_back(fmt::format("{}", static_cast<std::int32_t>(bits)));
  } else if (info.shape == OperandShape::kBoolDefinition) {
    operands.push_back(instruction.def_bits[0] != 0 ? "true" : "false");
  }
  for (int s = 0; s < SourceCount(info, model); ++s) {
    operands.push_back(FormatSource(instruction.sources[s], syntax, model));
  }
  std::string text = instruction.predicated ? fmt::format("({}) ", FormatSource(instruction.predicate, syntax, model))
                                            : std::string();
  text += MnemonicText(instruction);
  for (std::size_t i = 0; i < operands.size(); ++i) text += (i == 0 ? " " : ", ") + operands[i];
  if (info.shape == OperandShape::kDefinition) text += DefNote(instruction);
  return text;
}

std::string Disassemble(const Program& program) {
  const Syntax syntax = SyntaxOf(program);
  std::string out = VersionLine(program.version, syntax) + "\n";
  std::size_t next_comment = 0;
  auto print_comments_before = [&](int index) {
    while (next_comment < program.comments.size() && program.comments[next_comment].before_instruction <= index) {
      out += CommentLine(program.comments[next_comment++]) + "\n";
    }
  };
  for (int i = 0; i < static_cast<int>(program.instructions.size()); ++i) {
    print_comments_before(i);
    out += FormatInstruction(program.instructions[i], syntax, program.model()) + "\n";
  }
  print_comments_before(static_cast<int>(program.instructions.size()));
  return out;
}

}  // namespace vs11
