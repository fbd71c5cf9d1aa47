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
// Later models (spec "vs_2_0" section, from Microsoft's tokens): the instruction token's parameter count
// (bits 24-27), comparison (16-18), predication flag (28) and co-issue flag (30); _sat (dest bit 20);
// the source modifiers _abs, -_abs and ! (logical not); a sampler dcl's texture type (bits 27-30).
constexpr int kLengthShift = 24;
constexpr std::uint32_t kLengthMask = 0xF;
constexpr int kComparisonShift = 16;
constexpr std::uint32_t kControlsMask = 0x00FF0000u;
constexpr std::uint32_t kPredicatedBit = 0x10000000u;
constexpr std::uint32_t kInstructionReservedLaterMask = 0xE0000000u;  // bit 29, co-issue, bit 31
constexpr std::uint32_t kSaturateBit = 1u << 20;
constexpr std::uint32_t kSourceModifierAbs = 0xB;
constexpr std::uint32_t kSourceModifierAbsNegate = 0xC;
constexpr std::uint32_t kSourceModifierNot = 0xD;
constexpr int kSamplerTypeShift = 27;
constexpr std::uint32_t kSamplerUsageMask = 0xF8000000u;

std::uint32_t EncodeRegisterType(RegisterFile file) {
  auto type = static_cast<std::uint32_t>(file);
  return ((type & 7u) << 28) | ((type << 8) & 0x1800u);
}

std::uint32_t DecodeRegisterType(std::uint32_t token) { return ((token >> 28) & 7u) | ((token >> 8) & 0x18u); }

std::uint32_t EncodeDest(const DestOperand& dest) {
  return kParameterBit | EncodeRegisterType(dest.reg.file) |
         (static_cast<std::uint32_t>(dest.mask.bits()) << kWriteMaskShift) | (dest.saturate ? kSaturateBit : 0u) |
         (dest.reg.relative ? kRelativeBit : 0u) | (static_cast<std::uint32_t>(dest.reg.index) & kRegisterNumberMask);
}

std::uint32_t SourceModifierBits(const SourceOperand& source) {
  if (source.logical_not) return kSourceModifierNot;
  if (source.absolute) return source.negate ? kSourceModifierAbsNegate : kSourceModifierAbs;
  return source.negate ? kSourceModifierNegate : 0u;
}

std::uint32_t EncodeSource(const SourceOperand& source) {
  return kParameterBit | EncodeRegisterType(source.reg.file) | (SourceModifierBits(source) << kSourceModifierShift) |
         (static_cast<std::uint32_t>(source.swizzle.bits()) << kSwizzleShift) |
         (source.reg.relative ? kRelativeBit : 0u) |
         (static_cast<std::uint32_t>(source.reg.index) & kRegisterNumberMask);
}

// From vs_2_0 on, a relative operand is followed by a token naming its address register (a0 with a
// swizzle, or aL); vs_1_1's relative constant always means a0.x and has none.
std::uint32_t EncodeAddressToken(const AddressRegister& address) {
  return kParameterBit | EncodeRegisterType(address.file) |
         (static_cast<std::uint32_t>(address.swizzle_bits) << kSwizzleShift);
}

// The parameter tokens of `instruction` in a program of `model`, without the instruction token.
std::vector<std::uint32_t> EncodeParameters(const Instruction& instruction, ShaderModel model) {
  const OpcodeInfo& info = instruction.info();
  const bool address_tokens = model != ShaderModel::kVs11;
  std::vector<std::uint32_t> words;
  auto register_operand = [&](std::uint32_t token, const RegisterRef& reg) {
    words.push_back(token);
    if (reg.relative && address_tokens) words.push_back(EncodeAddressToken(reg.address));
  };
  switch (info.shape) {
    case OperandShape::kNone: break;
    case OperandShape::kDeclaration:
      words.push_back(instruction.dest.reg.file == RegisterFile::kSampler
                          ? kParameterBit | (static_cast<std::uint32_t>(instruction.sampler_type) << kSamplerTypeShift)
                          : kParameterBit |
                                (static_cast<std::uint32_t>(instruction.usage_index) << kUsageIndexShift) |
                                static_cast<std::uint32_t>(instruction.usage));
      words.push_back(EncodeDest(instruction.dest));
      break;
    case OperandShape::kDefinition:
    case OperandShape::kIntDefinition:
      words.push_back(EncodeDest(instruction.dest));
      words.insert(words.end(), instruction.def_bits.begin(), instruction.def_bits.end());
      break;
    case OperandShape::kBoolDefinition:
      words.push_back(EncodeDest(instruction.dest));
      words.push_back(instruction.def_bits[0]);
      break;
    default:
      if (info.has_dest()) register_operand(EncodeDest(instruction.dest), instruction.dest.reg);
      if (instruction.predicated) words.push_back(EncodeSource(instruction.predicate));
      for (int s = 0; s < SourceCount(info, model); ++s) {
        register_operand(EncodeSource(instruction.sources[s]), instruction.sources[s].reg);
      }
  }
  return words;
}

std::uint32_t EncodeInstructionToken(const Instruction& instruction, ShaderModel model, std::size_t parameters) {
  std::uint32_t token = instruction.info().token;
  if (model == ShaderModel::kVs11) return token;
  token |= static_cast<std::uint32_t>(parameters) << kLengthShift;
  if (TakesComparison(instruction.opcode)) token |= static_cast<std::uint32_t>(instruction.comparison) << kComparisonShift;
  if (instruction.predicated) token |= kPredicatedBit;
  return token;
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
           fmt::format("version token 0x{:08X} is not vs_1_1 (0xFFFE0101) or vs_1_0 (0xFFFE0100), nor vs_2_0 "
                       "(0xFFFE0200), vs_2_x (0xFFFE0201) or vs_3_0 (0xFFFE0300)",
                       words_[0]));
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
      std::optional<Opcode> opcode;
      std::size_t needed = 0;
      if (!ReadInstructionToken(p, token, opcode, needed)) break;
      const OpcodeInfo& info = Info(*opcode);
      Instruction instruction;
      instruction.opcode = *opcode;
      if (model_ != ShaderModel::kVs11) {
        if (TakesComparison(*opcode)) instruction.comparison = static_cast<int>((token >> kComparisonShift) & 7u);
        instruction.predicated = (token & kPredicatedBit) != 0;
      }
      std::size_t q = p + 1;
      if (DecodeParameters(info, q, p + 1 + needed, instruction)) {
        if (model_ != ShaderModel::kVs11 && q != p + 1 + needed) {
          Fail(p, DiagnosticCode::kBytecodeMalformedToken,
               fmt::format("{}'s length field says {} parameter tokens, its operands take {}", info.mnemonic,
                           needed, q - p - 1));
          break;
        }
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

  // The instruction token at `p`: its opcode and how many parameter tokens follow (vs_1_1: by the
  // operand shape, §4.3; later models: the length field, checked against the stream's end).
  bool ReadInstructionToken(std::size_t p, std::uint32_t token, std::optional<Opcode>& opcode, std::size_t& needed) {
    const auto opcode_bits = static_cast<std::uint16_t>(token & 0xFFFF);
    const bool later = model_ != ShaderModel::kVs11;
    if (!later && (token & kInstructionReservedMask)) {
      Fail(p, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("instruction token 0x{:08X} has bits set above the opcode (vs_1_1 has no "
                       "length, controls, predication or co-issue)", token));
      return false;
    }
    if (later && (token & kInstructionReservedLaterMask)) {
      Fail(p, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("instruction token 0x{:08X} has co-issue or reserved bits 29-31 set", token));
      return false;
    }
    opcode = OpcodeFromToken(opcode_bits);
    if (!opcode || !OpcodeAllowed(Info(*opcode), model_)) {
      Fail(p, DiagnosticCode::kBytecodeUnknownOpcode, fmt::format("opcode {} (0x{:04X}) is not a {} instruction",
                                                                  opcode_bits, opcode_bits, ShaderModelName(model_)));
      return false;
    }
    const OpcodeInfo& info = Info(*opcode);
    if (later) {
      const std::uint32_t controls = (token & kControlsMask) >> kComparisonShift;
      const bool comparison_ok = TakesComparison(*opcode) ? controls >= 1 && controls <= 6 : controls == 0;
      if (!comparison_ok) {
        Fail(p, DiagnosticCode::kBytecodeMalformedToken,
             fmt::format("{} has controls {} in bits 16-23 ({})", info.mnemonic, controls,
                         TakesComparison(*opcode) ? "a comparison is 1-6" : "it takes none"));
        return false;
      }
      if ((token & kPredicatedBit) && (!RegisterCount(RegisterFile::kPredicate, model_) || !info.is_executable())) {
        Fail(p, DiagnosticCode::kBytecodeMalformedToken,
             fmt::format("{} has the predication bit, which {} does not allow there", info.mnemonic,
                         ShaderModelName(model_)));
        return false;
      }
    }
    needed = later ? (token >> kLengthShift) & kLengthMask : static_cast<std::size_t>(info.parameter_tokens());
    if (needed > words_.size() - p - 1) {
      Fail(p, DiagnosticCode::kBytecodeTruncated,
           fmt::format("{} needs {} parameter tokens but the stream ends after {}", info.mnemonic, needed,
                       words_.size() - p - 1));
      return false;
    }
    return true;
  }

  // The next parameter word (at q, before `end`), or a truncation error.
  bool Take(std::size_t& q, std::size_t end, std::string_view mnemonic) {
    if (q < end) return true;
    Fail(q, DiagnosticCode::kBytecodeMalformedToken,
         fmt::format("{}'s length field leaves out some of its operands", mnemonic));
    return false;
  }

  // A later model's address token after a relative operand: a0 with a swizzle, or aL.
  bool DecodeAddressToken(std::size_t& q, std::size_t end, std::string_view mnemonic, RegisterRef& reg) {
    if (model_ == ShaderModel::kVs11 || !reg.relative) return true;
    if (!Take(q, end, mnemonic)) return false;
    const std::uint32_t token = words_[q];
    const std::uint32_t type = DecodeRegisterType(token);
    const bool loop = type == static_cast<std::uint32_t>(RegisterFile::kLoop) && RegisterFileOfType(type, model_);
    if (!(token & kParameterBit) || (type != static_cast<std::uint32_t>(RegisterFile::kAddress) && !loop) ||
        (token & ~(kParameterBit | 0x70001800u | 0x00FF0000u)) != 0) {
      Fail(q, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("relative-address token 0x{:08X} does not name a0 or aL", token));
      return false;
    }
    reg.address = AddressRegister{static_cast<RegisterFile>(type), static_cast<std::uint8_t>(token >> kSwizzleShift)};
    ++q;
    return true;
  }

  bool DecodeDest(std::size_t at, DestOperand& dest) {
    if (!CheckParameter(at)) return false;
    std::uint32_t token = words_[at];
    const std::uint32_t modifiers = model_ == ShaderModel::kVs11 ? token & kDestModifierAndShiftMask
                                                                   : token & kDestModifierAndShiftMask & ~kSaturateBit;
    if (modifiers) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("destination has a result modifier or shift, which {} does not have{}", ShaderModelName(model_),
                       model_ == ShaderModel::kVs11 ? "" : " (only _sat)"));
      return false;
    }
    if ((token & kRelativeBit) && model_ < ShaderModel::kVs30) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           fmt::format("destination has the relative-addressing bit, which {} does not allow", ShaderModelName(model_)));
      return false;
    }
    dest.reg.file = static_cast<RegisterFile>(DecodeRegisterType(token));
    dest.reg.index = static_cast<int>(token & kRegisterNumberMask);
    dest.reg.relative = (token & kRelativeBit) != 0;
    dest.mask = WriteMask(static_cast<std::uint8_t>((token >> kWriteMaskShift) & 0xF));
    dest.saturate = (token & kSaturateBit) != 0;
    return true;
  }

  bool DecodeSource(std::size_t at, SourceOperand& source) {
    if (!CheckParameter(at)) return false;
    std::uint32_t token = words_[at];
    std::uint32_t modifier = (token >> kSourceModifierShift) & 0xF;
    const bool later_modifier = model_ != ShaderModel::kVs11 && (modifier == kSourceModifierAbs ||
                                                                 modifier == kSourceModifierAbsNegate ||
                                                                 modifier == kSourceModifierNot);
    if (modifier > kSourceModifierNegate && !later_modifier) {
      Fail(at, DiagnosticCode::kBytecodeMalformedToken,
           model_ == ShaderModel::kVs11
               ? fmt::format("source modifier {} is not available in vs_1_1 (only negation)", modifier)
               : fmt::format("source modifier {} is not available in vertex shaders (negation, _abs and !)", modifier));
      return false;
    }
    source.reg.file = static_cast<RegisterFile>(DecodeRegisterType(token));
    source.reg.index = static_cast<int>(token & kRegisterNumberMask);
    source.reg.relative = (token & kRelativeBit) != 0;
    source.swizzle = Swizzle(static_cast<std::uint8_t>((token >> kSwizzleShift) & 0xFF));
    source.negate = modifier == kSourceModifierNegate || modifier == kSourceModifierAbsNegate;
    source.absolute = modifier == kSourceModifierAbs || modifier == kSourceModifierAbsNegate;
    source.logical_not = modifier == kSourceModifierNot;
    return true;
  }

  bool DecodeOperand(std::size_t& q, std::size_t end, std::string_view mnemonic, SourceOperand& source) {
    if (!Take(q, end, mnemonic) || !DecodeSource(q, source)) return false;
    ++q;
    return DecodeAddressToken(q, end, mnemonic, source.reg);
  }

  // A dcl's usage token: a D3DDECLUSAGE and index, or for a sampler (vs_3_0) its texture type.
  bool DecodeUsage(std::size_t at, Instruction& instruction) {
    const std::uint32_t usage = words_[at];
    const auto sampler_type = static_cast<std::uint32_t>(RegisterFile::kSampler);
    const bool sampler = RegisterFileOfType(sampler_type, model_) && at + 1 < words_.size() &&
                         DecodeRegisterType(words_[at + 1]) == sampler_type;
    if (sampler) {
      const std::uint32_t type = (usage >> kSamplerTypeShift) & 0xF;
      if ((usage & ~kSamplerUsageMask) != 0 || !(usage & kParameterBit) || type >= kSamplerTypeNames.size() ||
          kSamplerTypeNames[type].empty()) {
        Fail(at, DiagnosticCode::kBytecodeDeclarationUsage,
             fmt::format("sampler dcl token 0x{:08X} has no texture type 2d, cube or volume", usage));
        return false;
      }
      instruction.sampler_type = static_cast<int>(type);
      return true;
    }
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
    return true;
  }

  // The parameter tokens from q (advanced past what was read) up to `end` (the instruction's length).
  bool DecodeParameters(const OpcodeInfo& info, std::size_t& q, std::size_t end, Instruction& instruction) {
    switch (info.shape) {
      case OperandShape::kNone: return true;
      case OperandShape::kDeclaration:
        if (end - q < 2) return Take(end, end, info.mnemonic);
        if (!DecodeUsage(q, instruction) || !DecodeDest(q + 1, instruction.dest)) return false;
        q += 2;
        return true;
      case OperandShape::kDefinition:
      case OperandShape::kIntDefinition:
      case OperandShape::kBoolDefinition: {
        const std::size_t values = info.shape == OperandShape::kBoolDefinition ? 1 : 4;
        if (end - q < 1 + values) return Take(end, end, info.mnemonic);
        if (!DecodeDest(q, instruction.dest)) return false;
        for (std::size_t i = 0; i < values; ++i) instruction.def_bits[i] = words_[q + 1 + i];
        q += 1 + values;
        return true;
      }
      default:
        if (info.has_dest()) {
          if (!Take(q, end, info.mnemonic) || !DecodeDest(q, instruction.dest)) return false;
          ++q;
          if (!DecodeAddressToken(q, end, info.mnemonic, instruction.dest.reg)) return false;
        }
        if (instruction.predicated && !DecodeOperand(q, end, info.mnemonic, instruction.predicate)) return false;
        for (int s = 0; s < SourceCount(info, model_); ++s) {
          if (!DecodeOperand(q, end, info.mnemonic, instruction.sources[s])) return false;
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
  const ShaderModel model = program.model();
  for (int i = 0; i < static_cast<int>(program.instructions.size()); ++i) {
    emit_comments_before(i);
    const Instruction& instruction = program.instructions[i];
    const std::vector<std::uint32_t> parameters = EncodeParameters(instruction, model);
    words.push_back(EncodeInstructionToken(instruction, model, parameters.size()));
    words.insert(words.end(), parameters.begin(), parameters.end());
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
