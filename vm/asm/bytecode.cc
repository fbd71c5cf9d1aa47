#include "vm/asm/bytecode.h"

#include <fmt/format.h>

#include "vm/asm/lexer.h"

namespace vs11 {
namespace {

// Token fields (§4.3-§4.5).
constexpr std::uint32_t kParameterBit = 0x80000000u;
constexpr std::uint32_t kRegisterNumberMask = 0x7FF;
constexpr std::uint32_t kRelativeBit = 1u << 13;
constexpr std::uint32_t kReservedParameterBits = 3u << 14;
constexpr int kWriteMaskShift = 16;
constexpr int kSwizzleShift = 16;
constexpr int kSourceModifierShift = 24;
constexpr std::uint32_t kSourceModifierNegate = 1;
constexpr std::uint32_t kDestModifierAndShiftMask = 0x0FF00000u;  // result modifier + shift scale
constexpr std::uint32_t kInstructionReservedMask = 0xFFFF0000u;
constexpr std::uint32_t kUsageTokenMask = 0x800F000Fu;
constexpr int kUsageIndexShift = 16;

std::uint32_t EncodeRegisterType(RegisterFile file) {
  auto type = static_cast<std::uint32_t>(file);
  return ((type & 7u) << 28) | ((type << 8) & 0x1800u);
}

std::uint32_t DecodeRegisterType(std::uint32_t token) { return ((token >> 28) & 7u) | ((token >> 8) & 0x18u); }

std::uint32_t EncodeDest(const DestOperand& dest) {
  return kParameterBit | EncodeRegisterType(dest.reg.file) |
         (static_cast<std::uint32_t>(dest.mask.bits()) << kWriteMaskShift) |
         (static_cast<std::uint32_t>(dest.reg.index) & kRegisterNumberMask);
}

std::uint32_t EncodeSource(const SourceOperand& source) {
  return kParameterBit | EncodeRegisterType(source.reg.file) |
         (source.negate ? kSourceModifierNegate << kSourceModifierShift : 0u) |
         (static_cast<std::uint32_t>(source.swizzle.bits()) << kSwizzleShift) |
         (source.reg.relative ? kRelativeBit : 0u) |
         (static_cast<std::uint32_t>(source.reg.index) & kRegisterNumberMask);
}

class Decoder {
 public:
  explicit Decoder(std::span<const std::uint32_t> words) : words_(words) {}

  DecodeResult Run() {
    DecodeResult result;
    Program program;
    if (words_.empty()) {
      Fail(0, DiagnosticCode::kBytecodeTruncated, "empty token stream: expected the version token 0xFFFE0101");
      result.diagnostics = std::move(diagnostics_);
      return result;
    }
    if (!VersionEnabled(words_[0])) {
      Fail(0, DiagnosticCode::kVersionToken,
           fmt::format("version token 0x{:08X} is not vs_1_1 (0xFFFE0101) or vs_1_0 (0xFFFE0100)", words_[0]));
    }
    program.version = words_[0];
    model_ = program.model();
    std::size_t p = 1;
    bool ended = false;
    while (p < words_.size() && !diagnostics_.HasErrors()) {
      std::uint32_t token = words_[p];
      if (token == kEndToken) {
        if (p + 1 != words_.size()) Fail(p + 1, DiagnosticCode::kBytecodeTrailingWords,
                                         fmt::format("{} words after the end token", words_.size() - p - 1));
        ended = true;
        break;
      }
      auto opcode_bits = static_cast<std::uint16_t>(token & 0xFFFF);
      if (opcode_bits == kCommentOpcode) {
        if (token & kParameterBit) {
          Fail(p, DiagnosticCode::kBytecodeMalformedToken, "comment token has bit 31 set");
          break;
        }
        std::size_t count = (token >> 16) & kMaxCommentWords;
        if (count > words_.size() - p - 1) {
          Fail(p, DiagnosticCode::kBytecodeTruncated,
               fmt::format("comment of {} words runs past the end of the stream ({} words left)", count,
                              words_.size() - p - 1));
          break;
        }
        CommentBlock block{static_cast<int>(program.instructions.size()),
                           {words_.begin() + p + 1, words_.begin() + p + 1 + count}};
        program.comments.push_back(std::move(block));
        p += 1 + count;
        continue;
      }
      if (token & kInstructionReservedMask) {
        Fail(p, DiagnosticCode::kBytecodeMalformedToken,
             fmt::format("instruction token 0x{:08X} has bits set above the opcode (vs_1_1 has no "
                            "length, controls, predication or co-issue)", token));
        break;
      }
      std::optional<Opcode> opcode = OpcodeFromToken(opcode_bits);
      if (!opcode || !OpcodeAllowed(Info(*opcode), model_)) {
        Fail(p, DiagnosticCode::kBytecodeUnknownOpcode, fmt::format("opcode {} (0x{:04X}) is not a {} instruction",
                                                                    opcode_bits, opcode_bits, ShaderModelName(model_)));
        break;
      }
      const OpcodeInfo& info = Info(*opcode);
      std::size_t needed = static_cast<std::size_t>(info.parameter_tokens());
      if (needed > words_.size() - p - 1) {
        Fail(p, DiagnosticCode::kBytecodeTruncated,
             fmt::format("{} needs {} parameter tokens but the stream ends after {}", info.mnemonic, needed,
                            words_.size() - p - 1));
        break;
      }
      Instruction instruction;
      instruction.opcode = *opcode;
      if (DecodeParameters(info, p + 1, instruction)) {
        program.instructions.push_back(instruction);
        program.word_offsets.push_back(static_cast<long>(p));
      }
      p += 1 + needed;
    }
    if (!ended && !diagnostics_.HasErrors()) Fail(words_.size(), DiagnosticCode::kBytecodeTruncated,
                                                  "missing end token 0x0000FFFF");
    if (!diagnostics_.HasErrors()) result.program = std::move(program);
    result.diagnostics = std::move(diagnostics_);
    return result;
  }

 private:
  void Fail(std::size_t offset, DiagnosticCode code, std::string message) {
    Diagnostic d;
    d.code = code;
    d.message = std::move(message);
    d.word_offset = static_cast<long>(offset);
    diagnostics_.Add(std::move(d));
  }

  bool CheckParameter(std::size_t at) {
    std::uint32_t token = words_[at];
    if (!(token & kParameterBit)) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken, fmt::format("parameter token 0x{:08X} lacks bit 31", token));
      return false;
    }
    if (token & kReservedParameterBits) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("parameter token 0x{:08X} has reserved bits 14-15 set", token));
      return false;
    }
    std::uint32_t type = DecodeRegisterType(token);
    if (!RegisterFileOfType(type, model_)) {
      Fail(at, DiagnosticCode::kBytecodeRegisterType,
           fmt::format("register type {} is not used by {}", type, ShaderModelName(model_)));
      return false;
    }
    // Every register Decode accepts has a name, so that every decoded program can be disassembled.
    const int number = static_cast<int>(token & kRegisterNumberMask);
    if (!HasRegisterName(static_cast<RegisterFile>(type), number)) {
      Fail(at, DiagnosticCode::kBytecodeRegisterType,
           fmt::format("register type {} has no register {} in vs_1_1 (RASTOUT: 0 oPos, 1 oFog, 2 oPts)", type,
                           number));
      return false;
    }
    return true;
  }

  bool DecodeDest(std::size_t at, DestOperand& dest) {
    if (!CheckParameter(at)) return false;
    std::uint32_t token = words_[at];
    if (token & kDestModifierAndShiftMask) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           "destination has a result modifier or shift, which vs_1_1 does not have");
      return false;
    }
    if (token & kRelativeBit) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           "destination has the relative-addressing bit, which vs_1_1 does not allow");
      return false;
    }
    dest.reg.file = static_cast<RegisterFile>(DecodeRegisterType(token));
    dest.reg.index = static_cast<int>(token & kRegisterNumberMask);
    dest.mask = WriteMask(static_cast<std::uint8_t>((token >> kWriteMaskShift) & 0xF));
    return true;
  }

  bool DecodeSource(std::size_t at, SourceOperand& source) {
    if (!CheckParameter(at)) return false;
    std::uint32_t token = words_[at];
    std::uint32_t modifier = (token >> kSourceModifierShift) & 0xF;
    if (modifier > kSourceModifierNegate) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("source modifier {} is not available in vs_1_1 (only negation)", modifier));
      return false;
    }
    source.reg.file = static_cast<RegisterFile>(DecodeRegisterType(token));
    source.reg.index = static_cast<int>(token & kRegisterNumberMask);
    source.reg.relative = (token & kRelativeBit) != 0;
    source.swizzle = Swizzle(static_cast<std::uint8_t>((token >> kSwizzleShift) & 0xFF));
    source.negate = modifier == kSourceModifierNegate;
    return true;
  }

  bool DecodeParameters(const OpcodeInfo& info, std::size_t at, Instruction& instruction) {
    switch (info.shape) {
      case OperandShape::kNone: return true;
      case OperandShape::kDeclaration: {
        std::uint32_t usage = words_[at];
        if ((usage & ~kUsageTokenMask) != 0 || !(usage & kParameterBit)) {
          Fail(at, DiagnosticCode::kBytecodeDeclarationUsage,
               fmt::format("dcl usage token 0x{:08X} has reserved bits set", usage));
          return false;
        }
        instruction.usage = static_cast<int>(usage & 0xF);
        instruction.usage_index = static_cast<int>((usage >> kUsageIndexShift) & 0xF);
        if (instruction.usage >= static_cast<int>(kDeclUsageNames.size())) {
          Fail(at, DiagnosticCode::kBytecodeDeclarationUsage,
               fmt::format("dcl usage {} is not a D3DDECLUSAGE value", instruction.usage));
          return false;
        }
        return DecodeDest(at + 1, instruction.dest);
      }
      case OperandShape::kDefinition:
        if (!DecodeDest(at, instruction.dest)) return false;
        for (int i = 0; i < 4; ++i) instruction.def_bits[i] = words_[at + 1 + i];
        return true;
      default:
        if (!DecodeDest(at, instruction.dest)) return false;
        for (int s = 0; s < info.source_count(); ++s) {
          if (!DecodeSource(at + 1 + s, instruction.sources[s])) return false;
        }
        return true;
    }
  }

  ShaderModel model_ = ShaderModel::kVs11;
  std::span<const std::uint32_t> words_;
  Diagnostics diagnostics_;
};

}  // namespace

std::vector<std::uint32_t> Encode(const Program& program) {
  std::vector<std::uint32_t> words{program.version};
  std::size_t next_comment = 0;
  auto emit_comments_before = [&](int index) {
    while (next_comment < program.comments.size() && program.comments[next_comment].before_instruction <= index) {
      const CommentBlock& block = program.comments[next_comment++];
      words.push_back((static_cast<std::uint32_t>(block.words.size()) << 16) | kCommentOpcode);
      words.insert(words.end(), block.words.begin(), block.words.end());
    }
  };
  for (int i = 0; i < static_cast<int>(program.instructions.size()); ++i) {
    emit_comments_before(i);
    const Instruction& instruction = program.instructions[i];
    const OpcodeInfo& info = instruction.info();
    words.push_back(info.token);
    switch (info.shape) {
      case OperandShape::kNone: break;
      case OperandShape::kDeclaration:
        words.push_back(kParameterBit | (static_cast<std::uint32_t>(instruction.usage_index) << kUsageIndexShift) |
                        static_cast<std::uint32_t>(instruction.usage));
        words.push_back(EncodeDest(instruction.dest));
        break;
      case OperandShape::kDefinition:
        words.push_back(EncodeDest(instruction.dest));
        words.insert(words.end(), instruction.def_bits.begin(), instruction.def_bits.end());
        break;
      default:
        words.push_back(EncodeDest(instruction.dest));
        for (int s = 0; s < info.source_count(); ++s) words.push_back(EncodeSource(instruction.sources[s]));
    }
  }
  emit_comments_before(static_cast<int>(program.instructions.size()));
  words.push_back(kEndToken);
  return words;
}

DecodeResult Decode(std::span<const std::uint32_t> words) { return Decoder(words).Run(); }

std::optional<std::vector<std::uint32_t>> WordsFromBytes(std::span<const std::uint8_t> bytes) {
  if (bytes.size() % 4 != 0) return std::nullopt;
  std::vector<std::uint32_t> words(bytes.size() / 4);
  for (std::size_t i = 0; i < words.size(); ++i) {
    words[i] = static_cast<std::uint32_t>(bytes[4 * i]) | static_cast<std::uint32_t>(bytes[4 * i + 1]) << 8 |
               static_cast<std::uint32_t>(bytes[4 * i + 2]) << 16 | static_cast<std::uint32_t>(bytes[4 * i + 3]) << 24;
  }
  return words;
}

std::vector<std::uint8_t> BytesFromWords(std::span<const std::uint32_t> words) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(words.size() * 4);
  for (std::uint32_t w : words) {
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(static_cast<std::uint8_t>(w >> shift));
  }
  return bytes;
}

}  // namespace vs11
