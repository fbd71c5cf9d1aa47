#include "vm/asm/validator.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "vm/asm/disassembler.h"
#include "vm/asm/read_ports.h"

namespace vs11 {
namespace {

// ---------------------------------------------------------------------------------------------
// Lanes consumed by each source (§6.3). Written once, driven by the opcode table's ResultKind.

constexpr int kLaneCount = 4;
constexpr std::uint8_t kLaneX = 1 << 0;
constexpr std::uint8_t kLaneY = 1 << 1;
constexpr std::uint8_t kLaneZ = 1 << 2;
constexpr std::uint8_t kLaneW = 1 << 3;
constexpr std::uint8_t kLanesXyw = kLaneX | kLaneY | kLaneW;
constexpr std::uint8_t kAllLanes = WriteMask::kAllLanes;

// The source of m*x* that names the first row register of the matrix (§3.4: `m4x4 d, S, M`).

// kVector rows (lit, dst, expp, logp) share no lane formula, so for each of them this table lists
// which lanes of each *swizzled* source every written destination lane needs (§3.3, §6.3).
struct VectorLaneRule {
  Opcode opcode;
  bool scalar_source;  // reads one lane of s0 (its w selector) like kScalar rows (§3.1)
  std::array<std::array<std::uint8_t, kLaneCount>, 2> needs;  // [source][destination lane]
};
constexpr std::array kVectorLaneRules = {
    // lit: x, y, w whatever the mask (§6.3; the native per-lane rule is unconfirmed, §10.14).
    VectorLaneRule{Opcode::kLit, false, {{{kLanesXyw, kLanesXyw, kLanesXyw, kLanesXyw}, {}}}},
    // dst: r.x = 1, r.y = a.y * b.y, r.z = a.z, r.w = b.w.
    VectorLaneRule{Opcode::kDst, false, {{{0, kLaneY, kLaneZ, 0}, {0, kLaneY, 0, kLaneW}}}},
    // expp, logp: every result lane comes from the scalar w (§3.1, §3.3).
    VectorLaneRule{Opcode::kExpp, true, {{{kLaneW, kLaneW, kLaneW, kLaneW}, {}}}},
    VectorLaneRule{Opcode::kLogp, true, {{{kLaneW, kLaneW, kLaneW, kLaneW}, {}}}},
};

constexpr const VectorLaneRule* FindVectorLaneRule(Opcode opcode) {
  for (const VectorLaneRule& rule : kVectorLaneRules) {
    if (rule.opcode == opcode) return &rule;
  }
  return nullptr;
}

// Every kVector row of vs_1_1 must have a lane rule above (ConsumedLanes says every lane for the later
// models' rows; their own lanes are in temporary_dataflow.cc).
static_assert([] {
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (info.kind == ResultKind::kVector && info.since == ShaderModel::kVs11 &&
        FindVectorLaneRule(info.opcode) == nullptr) {
      return false;
    }
  }
  return true;
}());

// Lanes 0 .. width-1.
constexpr std::uint8_t LowLanes(int width) { return static_cast<std::uint8_t>((1u << width) - 1); }

// Lanes of the swizzled source value (before the swizzle maps them onto register lanes).
std::uint8_t NeededSwizzledLanes(const OpcodeInfo& info, int operand, WriteMask dest_mask) {
  switch (info.kind) {
    case ResultKind::kComponentwise:
      return dest_mask.bits() & kAllLanes;
    case ResultKind::kDotProduct:
    case ResultKind::kMatrix:
      return LowLanes(info.dot_width);
    case ResultKind::kScalar:
      return kLaneW;
    case ResultKind::kVector: {
      const VectorLaneRule* rule = FindVectorLaneRule(info.opcode);
      if (rule == nullptr) return kAllLanes;  // a later model's row
      assert(operand < 2);
      std::uint8_t lanes = 0;
      for (int lane = 0; lane < kLaneCount; ++lane) {
        if (dest_mask.has(lane)) lanes |= rule->needs[operand][lane];
      }
      return lanes;
    }
    case ResultKind::kNoResult:
      return 0;
  }
  return 0;
}

// Does the instruction compute from a single lane of its source (§3.1)?
bool ReadsScalarSource(const OpcodeInfo& info) {
  if (info.kind == ResultKind::kScalar) return true;
  const VectorLaneRule* rule = FindVectorLaneRule(info.opcode);
  return rule != nullptr && rule->scalar_source;
}

// ---------------------------------------------------------------------------------------------
// Register files (§1.1, §1.6, §6.2.1-2).

// How many registers each file has is the program's model's (vm/core/shader_model.h), but for the
// constants, whose count the device gives (ValidatorOptions::constant_count).
struct RegisterFileRule {
  RegisterFile file;
  bool readable;  // may be a source
  bool writable;  // may be an instruction destination
  std::string_view role;
};
constexpr std::array kRegisterFileRules = {
    RegisterFileRule{RegisterFile::kTemp, true, true, "temporary"},
    RegisterFileRule{RegisterFile::kInput, true, false, "input"},
    RegisterFileRule{RegisterFile::kConst, true, false, "constant"},
    RegisterFileRule{RegisterFile::kAddress, false, true, "address"},
    RegisterFileRule{RegisterFile::kRasterOut, false, true, "output"},
    RegisterFileRule{RegisterFile::kAttributeOut, false, true, "output"},
    RegisterFileRule{RegisterFile::kTexCoordOut, false, true, "output"},
    RegisterFileRule{RegisterFile::kConstInt, true, false, "integer constant"},
    RegisterFileRule{RegisterFile::kConstBool, true, false, "boolean constant"},
    RegisterFileRule{RegisterFile::kLoop, true, false, "loop counter"},
    RegisterFileRule{RegisterFile::kPredicate, true, true, "predicate"},
};

// The first model that has registers of `file`.
std::string_view FirstModelWith(RegisterFile file) {
  for (const ShaderModelInfo& model : kShaderModels) {
    if (RegisterCount(file, model.model) > 0) return model.name;
  }
  return "no vertex shader model";
}

const RegisterFileRule* FindRegisterFileRule(RegisterFile file) {
  for (const RegisterFileRule& rule : kRegisterFileRules) {
    if (rule.file == file) return &rule;
  }
  return nullptr;
}

// "r3", "oT1", "c5[a0.x]": the disassembler's spelling, so that messages match the listing.
std::string RegisterName(const RegisterRef& reg) { return FormatSource(SourceOperand{reg, Swizzle(), false}); }

// ".xz" for lanes {x, z}.
std::string LaneSuffix(std::uint8_t lanes) {
  std::string text = ".";
  for (int lane = 0; lane < kLaneCount; ++lane) {
    if (lanes & (1 << lane)) text += kLaneLetters[lane];
  }
  return text;
}

// The register a source reads for matrix row `row` (row 0 for ordinary sources).
RegisterRef RowRegister(RegisterRef reg, int row) {
  reg.index += row;
  return reg;
}

// ---------------------------------------------------------------------------------------------
// Destination mask rules of the opcode table (§3.2).

bool MaskAllowed(MaskRule rule, WriteMask mask) {
  switch (rule) {
    case MaskRule::kAny:
      return true;
    case MaskRule::kYOrXy:
      return mask.bits() == kLaneY || mask.bits() == (kLaneX | kLaneY);
    case MaskRule::kXy:
      return mask.bits() == (kLaneX | kLaneY);
    case MaskRule::kXyz:
      return mask.bits() == (kLaneX | kLaneY | kLaneZ);
    case MaskRule::kXyzw:
    case MaskRule::kFull:
      return mask.is_full();
  }
  return false;
}

std::string_view MaskRuleText(MaskRule rule) {
  switch (rule) {
    case MaskRule::kAny:
      return "any mask";
    case MaskRule::kYOrXy:
      return ".y or .xy";
    case MaskRule::kXy:
      return ".xy";
    case MaskRule::kXyz:
      return ".xyz";
    case MaskRule::kXyzw:
    case MaskRule::kFull:
      return ".xyzw (no mask)";
  }
  return "";
}

// ---------------------------------------------------------------------------------------------

class Validator {
 public:
  Validator(const Program& program, const ValidatorOptions& options)
      : program_(program), options_(options), dx9_(UsesDx9Rules(program, options)) {
    declared_at_.fill(-1);
  }

  Diagnostics Run() {
    CheckVersion();
    CollectDeclarations();
    for (int i = 0; i < static_cast<int>(program_.instructions.size()); ++i) CheckInstruction(i);
    if (options_.require_position) CheckPositionWritten();
    return std::move(diagnostics_);
  }

 private:
  static bool UsesDx9Rules(const Program& program, const ValidatorOptions& options) {
    using Dialect = ValidatorOptions::Dialect;
    if (options.dialect != Dialect::kAuto) return options.dialect == Dialect::kDx9;
    return std::any_of(program.instructions.begin(), program.instructions.end(),
                       [](const Instruction& instruction) { return instruction.opcode == Opcode::kDcl; });
  }

  const Instruction& At(int index) const { return program_.instructions[index]; }

  // "dp4" when the instruction has a source line, "instruction 3 (dp4)" when it does not.
  std::string Subject(int index) const {
    const SourceLoc loc = program_.LocOf(index);
    std::string_view mnemonic = At(index).info().mnemonic;
    if (loc.line > 0) return std::string(mnemonic);
    return fmt::format("instruction {} ({})", index, mnemonic);
  }

  void Error(int index, DiagnosticCode code, std::string_view message) {
    Report(Severity::kError, code, index, message);
  }
  void Warning(int index, DiagnosticCode code, std::string_view message) {
    Report(Severity::kWarning, code, index, message);
  }
  // At the source line, or for bytecode at the word of the instruction token.
  void Report(Severity severity, DiagnosticCode code, int index, std::string_view message) {
    diagnostics_.Add(Diagnostic{program_.LocOf(index), severity, code, fmt::format("{}: {}", Subject(index), message),
                                program_.WordOffsetOf(index)});
  }
  // Whole-program problems point at the file only.
  SourceLoc ProgramLoc() const {
    return program_.source_locs.empty() ? SourceLoc{} : SourceLoc{program_.source_locs.front().file, 0, 0};
  }

  bool IsVersion10() const { return program_.version == kVersionVs10; }

  // --- structure (§6.1) ------------------------------------------------------------------------

  void CheckVersion() {
    if (VersionEnabled(program_.version)) return;
    diagnostics_.Error(ProgramLoc(), DiagnosticCode::kVersionToken,
                       fmt::format("version token 0x{:08X} is not vs_1_1 (0x{:08X}) or vs_1_0 "
                                                 "(0x{:08X}); start the program with vs_1_1",
                                                 program_.version, kVersionVs11, kVersionVs10));
  }

  void CheckPlacementAndSlots(int index) {
    const OpcodeInfo& info = At(index).info();
    if (!info.is_executable()) {
      if (first_executable_ >= 0) {
        Error(index, DiagnosticCode::kMisplacedDeclaration,
              fmt::format("appears after the first executable instruction ({}); move every dcl and "
                                 "def above it (§3.3)",
                                 Where(first_executable_)));
      }
      return;
    }
    if (first_executable_ < 0) first_executable_ = index;
    const int before = slots_;
    slots_ += info.slots;
    if (before <= kMaxInstructionSlots && slots_ > kMaxInstructionSlots) {
      Error(index, DiagnosticCode::kTooManySlots,
            fmt::format("takes the program to {} instruction slots, over the vs_1_1 limit of {} "
                               "(macros count several slots: §2.7); shorten the program",
                               slots_, kMaxInstructionSlots));
    }
  }

  void CheckInstruction(int index) {
    const Instruction& instruction = At(index);
    if (!OpcodeAllowed(instruction.info(), program_.model())) {  // the opcode table's model column
      Error(index, DiagnosticCode::kUnknownInstruction,
            fmt::format("{} is not a {} instruction (it exists from {} on)", instruction.info().mnemonic,
                        ShaderModelName(program_.model()), ShaderModelName(instruction.info().since)));
      return;
    }
    CheckPlacementAndSlots(index);
    if (instruction.opcode == Opcode::kDcl) {
      CheckDeclaration(index);
      return;
    }
    if (instruction.opcode == Opcode::kDef) {
      CheckDefinition(index);
      return;
    }
    if (!instruction.info().has_dest()) return;  // nop
    CheckDestination(index);
    CheckMask(index);
    CheckSources(index);
    CheckReadPorts(index);
    CheckMatrixOperands(index);
    CheckScalarSwizzle(index);
    CheckTemporaryReads(index);
    CheckInputDeclarations(index);
    RecordWrites(index);
  }

  // --- register ranges and types (§6.2.1-2) ----------------------------------------------------

  // Reports `reg` if its number does not exist; `what` says where it was used.
  bool CheckRange(int index, const RegisterRef& reg, std::string_view what) {
    const RegisterFileRule* rule = FindRegisterFileRule(reg.file);
    if (rule == nullptr) {
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} has register type {}, which {} does not have", what, static_cast<int>(reg.file),
                        ShaderModelName(program_.model())));
      return false;
    }
    const ShaderModel model = program_.model();
    const int count = reg.file == RegisterFile::kConst ? options_.constant_count : RegisterCount(reg.file, model);
    if (reg.index >= 0 && reg.index < count) return true;
    if (count == 0) {
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} names {}, which {} does not have ({} registers exist from {} on)", what,
                        RegisterName(reg), ShaderModelName(model), rule->role, FirstModelWith(reg.file)));
      return false;
    }
    // Real vs_1_1 shaders use c100 and beyond on devices with 256 constants.
    const std::string more_constants =
        fmt::format("; for a device with more, give its count with --max-constants (e.g. --max-constants {})",
                    std::max(256, reg.index + 1));
    if (reg.relative) {
      // Only the offset can be checked statically; a0.x is known at run time (§1.4).
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} uses relative offset {}, outside 0-{} (the device has {} constants){}", what,
                               reg.index, count - 1, count, more_constants));
    } else if (reg.file == RegisterFile::kConst) {
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} names {}, but the device has only c0-c{} (MaxVertexShaderConst = {}){}", what,
                               RegisterName(reg), count - 1, count, more_constants));
    } else {
      RegisterRef last{reg.file, count - 1, false};
      std::string range = count == 1 ? RegisterName(last)
                                     : fmt::format("{}-{}", RegisterName({reg.file, 0, false}), RegisterName(last));
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} names {}, which does not exist; {} has {}", what, RegisterName(reg),
                        ShaderModelName(program_.model()), range));
    }
    return false;
  }

  void CheckDestination(int index) {
    const Instruction& instruction = At(index);
    const RegisterRef& reg = instruction.dest.reg;
    const RegisterFileRule* rule = FindRegisterFileRule(reg.file);
    if (rule != nullptr && !rule->writable && RegisterCount(reg.file, program_.model()) > 0) {
      Error(index, DiagnosticCode::kReadOnlyDestination,
            fmt::format("cannot write {}: {} registers are read-only; write a temporary (r#) or an "
                               "output instead",
                               RegisterName(reg), rule->role));
      return;
    }
    if (reg.relative) Error(index, DiagnosticCode::kRelativeAddressing,
                            "relative addressing is not allowed on a destination in vs_1_1");
    if (!CheckRange(index, reg, "the destination")) return;
    if (reg.file != RegisterFile::kAddress) return;
    if (IsVersion10()) Error(index, DiagnosticCode::kAddressWrite,
                             "writes a0, which vs_1_0 does not have; use vs_1_1 (§2.1)");
    if (!instruction.info().can_write_address()) Error(index, DiagnosticCode::kAddressWrite,
                                                       "cannot write a0; only mov can (mov a0.x, src)");
  }

  void CheckMask(int index) {
    const Instruction& instruction = At(index);
    const WriteMask mask = instruction.dest.mask;
    if (mask.bits() == 0) {
      Error(index, DiagnosticCode::kWriteMask,
            fmt::format("has an empty write mask on {}; write at least one lane", RegisterName(instruction.dest.reg)));
      return;
    }
    if (instruction.dest.reg.file == RegisterFile::kAddress) {
      if (mask.bits() != kLaneX) {
        Error(index, DiagnosticCode::kAddressWrite,
              fmt::format("writes a0{}; a0 only has .x: write a0.x", LaneSuffix(mask.bits())));
      }
      return;
    }
    if (IsScalarOutput(instruction.dest.reg) && !(mask.bits() & kLaneX)) {
      // Any mask is encodable and round-trips through text; but the rasterizer reads lane x only.
      const std::string name = RegisterName(instruction.dest.reg);
      Warning(index, DiagnosticCode::kScalarOutputMask,
              fmt::format("writes {}{}, but only lane x of {} is used (§7), so this write has no effect; "
                                 "write {} or {}.x",
                                 name, LaneSuffix(mask.bits()), name, name, name));
    }
    const MaskRule rule = instruction.info().mask_rule;
    if (!MaskAllowed(rule, mask)) {
      Error(index, DiagnosticCode::kWriteMask,
            fmt::format("write mask {} is not allowed; {} must write {} (§3.2)", LaneSuffix(mask.bits()),
                               instruction.info().mnemonic, MaskRuleText(rule)));
    }
  }

  void CheckSources(int index) {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    bool relative_reported = false;
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      const std::string what = fmt::format("src{}", s);
      const RegisterFileRule* rule = FindRegisterFileRule(reg.file);
      if (rule != nullptr && !rule->readable) {
        Error(index, DiagnosticCode::kWriteOnlySource, reg.file == RegisterFile::kAddress
                         ? "reads a0 as a source; a0 can only index constants, as c[a0.x + n]"
                         : fmt::format("reads {}, but output registers are write-only; keep the value in a "
                                       "temporary (r#) and read that",
                                       RegisterName(reg)));
        continue;
      }
      if (reg.relative && reg.file != RegisterFile::kConst) {
        Error(index, DiagnosticCode::kRelativeAddressing,
              fmt::format("{} uses relative addressing on {}; only constants can be addressed with a0.x", what,
                                 RegisterName({reg.file, reg.index, false})));
        continue;
      }
      for (int row = 0; row < info.registers_read(s); ++row) {
        if (!CheckRange(index, RowRegister(reg, row), what)) break;
      }
      if (reg.relative && !relative_reported) {
        relative_reported = true;
        CheckRelativeAddressing(index, reg);
      }
    }
  }

  void CheckRelativeAddressing(int index, const RegisterRef& reg) {
    if (IsVersion10()) {
      Error(index, DiagnosticCode::kRelativeAddressing,
            fmt::format("reads {}, but vs_1_0 has no a0; use vs_1_1 (§2.1)", RegisterName(reg)));
    } else if (!a0_written_) {
      Error(index, DiagnosticCode::kAddressNotWritten,
            fmt::format("reads {} before a0 is written; put `mov a0.x, <src>` earlier in the program",
                               RegisterName(reg)));
    }
  }

  // --- read ports (§1.7, §3.4): vm/asm/read_ports.h ------------------------------------------

  void CheckReadPorts(int index) {
    for (const ReadPortViolation& violation : FindReadPortViolations(At(index), program_.model())) {
      Error(index, DiagnosticCode::kReadPorts, DescribeReadPortViolation(violation, program_.model()));
    }
  }

  // --- matrix macros (§3.3) --------------------------------------------------------------------

  void CheckMatrixOperands(int index) {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    if (info.kind != ResultKind::kMatrix) return;
    const SourceOperand& matrix = instruction.sources[OpcodeInfo::kMatrixSource];
    if (!matrix.swizzle.is_identity()) {
      Error(index, DiagnosticCode::kMatrixOperand,
            fmt::format("the matrix operand {} cannot be swizzled; remove the swizzle",
                               FormatSource(SourceOperand{matrix.reg, matrix.swizzle, false})));
    }
    if (matrix.negate) {
      Error(index, DiagnosticCode::kMatrixOperand,
            fmt::format("the matrix operand -{} cannot be negated; negate the first source instead",
                               RegisterName(matrix.reg)));
    }
    const RegisterRef& dest = instruction.dest.reg;
    if (dest == instruction.sources[0].reg) {
      Error(index, DiagnosticCode::kMatrixOperand,
            fmt::format("writes {}, which is also its first source; the expanded rows would read "
                               "partly overwritten values (§3.4): write a different register",
                               RegisterName(dest)));
    }
    for (int row = 0; row < info.matrix_rows; ++row) {
      if (dest == RowRegister(matrix.reg, row)) {
        Error(index, DiagnosticCode::kMatrixOperand,
              fmt::format("writes {}, which is also matrix row {} (§3.4); write a different register",
                                 RegisterName(dest), row));
      }
    }
  }

  // --- scalar swizzle (§3.1) -------------------------------------------------------------------

  void CheckScalarSwizzle(int index) {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    if (!ReadsScalarSource(info)) return;
    for (int s = 0; s < info.source_count(); ++s) {
      const SourceOperand& source = instruction.sources[s];
      if (source.swizzle.is_replicate()) continue;
      Warning(index, DiagnosticCode::kScalarSwizzle,
              fmt::format("reads a single lane, but {} has no replicate swizzle; the w lane is used "
                                 "(§3.1) — write {}.w (or .x, .y, .z) to say which",
                                 RegisterName(source.reg), RegisterName(source.reg)));
    }
  }

  // --- data flow (§6.3) ------------------------------------------------------------------------

  // Lanes of temporaries that instruction `index` reads before anything wrote them, per register.
  std::array<std::uint8_t, kTempRegisterCount> UnwrittenTemporaryLanes(int index) const {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    std::array<std::uint8_t, kTempRegisterCount> missing{};
    for (int s = 0; s < info.source_count(); ++s) {
      const SourceOperand& source = instruction.sources[s];
      if (source.reg.file != RegisterFile::kTemp) continue;
      const std::uint8_t lanes = ConsumedLanes(info, s, instruction.dest.mask, source.swizzle);
      for (int row = 0; row < info.registers_read(s); ++row) {
        const int reg = source.reg.index + row;
        if (reg < 0 || reg >= kTempRegisterCount) continue;  // reported by CheckSources
        missing[reg] |= lanes & ~written_lanes_[reg];
      }
    }
    return missing;
  }

  // A temporary that nothing wrote is an error in every dialect. Lanes that nothing wrote of one that
  // was partly written are an error under DX9 rules and with `strict`, and only a warning for DX8
  // programs: the D3D8 runtime ran Microsoft's own samples that read them (`m4x3 r4, ...` writes .xyz,
  // then `mul r4, r4, v1.xxxx` reads r4.w), and the engines read such lanes as 0.
  void CheckTemporaryReads(int index) {
    const std::array<std::uint8_t, kTempRegisterCount> missing = UnwrittenTemporaryLanes(index);
    std::vector<std::string> never_written, partly_written;
    for (int reg = 0; reg < kTempRegisterCount; ++reg) {
      if (missing[reg] == 0) continue;
      const std::string lanes = fmt::format("r{}{}", reg, LaneSuffix(missing[reg]));
      (written_lanes_[reg] == 0 ? never_written : partly_written).push_back(lanes);
    }
    if (!never_written.empty()) {
      Error(index, DiagnosticCode::kUninitializedRegister,
            fmt::format("reads {} before {} written; temporaries start undefined, so write {} earlier in the "
                        "program",
                        fmt::join(never_written, ", "), never_written.size() == 1 ? "it is" : "they are",
                        never_written.size() == 1 ? "it" : "them"));
    }
    if (partly_written.empty()) return;
    const std::string message =
        fmt::format("reads {}, which no earlier instruction writes; ", fmt::join(partly_written, ", "));
    if (dx9_ || options_.strict) {
      Error(index, DiagnosticCode::kUninitializedLanes,
            message + fmt::format("{} forbids that (as the D3D9 validator's \"read of uninitialized components\"): "
                                  "write those lanes earlier in the program",
                                  dx9_ ? "DX9 vs_1_1" : "--strict"));
    } else {
      Warning(index, DiagnosticCode::kUninitializedLanes,
              message + "they read 0 (the D3D8 runtime accepts this in DX8 programs; --strict refuses it)");
    }
  }

  void CollectDeclarations() {
    for (int i = 0; i < static_cast<int>(program_.instructions.size()); ++i) {
      const RegisterRef& reg = At(i).dest.reg;
      if (At(i).opcode != Opcode::kDcl || reg.file != RegisterFile::kInput) continue;
      if (reg.index < 0 || reg.index >= kInputRegisterCount || declared_at_[reg.index] >= 0) continue;
      declared_at_[reg.index] = i;
    }
  }

  void CheckInputDeclarations(int index) {
    if (!dx9_) return;
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    std::array<bool, kInputRegisterCount> reported{};
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& base = instruction.sources[s].reg;
      if (base.file != RegisterFile::kInput) continue;
      for (int row = 0; row < info.registers_read(s); ++row) {
        const int reg = base.index + row;
        if (reg < 0 || reg >= kInputRegisterCount || declared_at_[reg] >= 0 || reported[reg]) continue;
        reported[reg] = true;
        Error(index, DiagnosticCode::kUndeclaredInput,
              fmt::format("reads v{0}, which has no dcl; DX9 vs_1_1 needs a declaration such as "
                                 "`dcl_texcoord v{0}` before the first instruction (§1.2)",
                                 reg));
      }
    }
  }

  void RecordWrites(int index) {
    const Instruction& instruction = At(index);
    const RegisterRef& reg = instruction.dest.reg;
    const std::uint8_t mask = instruction.dest.mask.bits() & kAllLanes;
    if (reg.relative) return;
    if (reg.file == RegisterFile::kTemp && reg.index >= 0 && reg.index < kTempRegisterCount) {
      written_lanes_[reg.index] |= mask;
    } else if (reg.file == RegisterFile::kAddress) {
      a0_written_ = true;  // any mov to a0 (even with a bad mask, reported already)
    } else if (reg.file == RegisterFile::kRasterOut && reg.index == kRasterOutPosition && mask != 0) {
      position_lanes_ |= mask;
      last_position_write_ = index;
    }
  }

  void CheckPositionWritten() {
    if (position_lanes_ == 0) {
      diagnostics_.Error(ProgramLoc(), DiagnosticCode::kPositionNotWritten,
                         "the program never writes oPos; every vertex shader must output a "
                         "position (for example m4x4 oPos, v0, c0) (§6.3)");
    } else if (position_lanes_ != kAllLanes) {
      // Unconfirmed (§10.11): one source demands all four lanes, so this is only a warning.
      Warning(last_position_write_, DiagnosticCode::kPositionPartlyWritten,
              fmt::format("oPos is written only in lanes {}; write all four lanes (x, y, z, w) of the "
                          "position",
                          LaneSuffix(position_lanes_)));
    }
  }

  // --- dcl and def (§3.3, §6.2.8) --------------------------------------------------------------

  void CheckDeclaration(int index) {
    const Instruction& instruction = At(index);
    const RegisterRef& reg = instruction.dest.reg;
    if (reg.file != RegisterFile::kInput || reg.relative) {
      Error(index, DiagnosticCode::kBadDeclaration,
            fmt::format("declares {}; dcl can only declare an input register v0-v{}", RegisterName(reg),
                               kInputRegisterCount - 1));
      return;
    }
    if (!CheckRange(index, reg, "the declaration")) return;
    CheckMask(index);
    const int usage_count = static_cast<int>(kDeclUsageNames.size());
    if (instruction.usage < 0 || instruction.usage >= usage_count || instruction.usage_index < 0 ||
        instruction.usage_index > kMaxDeclUsageIndex) {
      Error(index, DiagnosticCode::kBadDeclaration,
            fmt::format("has usage {} index {}; usage must be 0-{} and index 0-{}", instruction.usage,
                               instruction.usage_index, usage_count - 1, kMaxDeclUsageIndex));
      return;
    }
    if (dx9_) CheckDuplicateDeclaration(index);
  }

  void CheckDuplicateDeclaration(int index) {
    const Instruction& instruction = At(index);
    const int reg = instruction.dest.reg.index;
    if (declared_at_[reg] != index) {
      Error(index, DiagnosticCode::kDuplicateDeclaration,
            fmt::format("declares v{} a second time (first dcl: {}); declare each input once", reg,
                               Where(declared_at_[reg])));
    }
    const std::string usage = fmt::format("dcl_{}{}", kDeclUsageNames[instruction.usage],
                                          instruction.usage_index > 0 ? std::to_string(instruction.usage_index) : "");
    const auto [it, inserted] =
        usage_declared_at_.emplace(std::pair(instruction.usage, instruction.usage_index), index);
    if (!inserted) {
      Error(index, DiagnosticCode::kDuplicateDeclaration,
            fmt::format("repeats {} (first used by {}); each usage and index can feed one input register", usage,
                               Where(it->second)));
    }
  }

  // "line 3" or "instruction 3".
  std::string Where(int index) const {
    const SourceLoc loc = program_.LocOf(index);
    return loc.line > 0 ? fmt::format("line {}", loc.line) : fmt::format("instruction {}", index);
  }

  void CheckDefinition(int index) {
    const RegisterRef& reg = At(index).dest.reg;
    if (reg.file != RegisterFile::kConst || reg.relative) {
      Error(index, DiagnosticCode::kBadDefinition,
            fmt::format("defines {}; def can only set an absolute constant register c#", RegisterName(reg)));
      return;
    }
    if (!CheckRange(index, reg, "the definition")) return;
    CheckMask(index);
    // The spec lets a later def of a register win (§3.3); more defs than registers can only be
    // redefinitions, so that is where a program stops: a hostile one cannot hold 100k of them.
    if (++definitions_ > options_.constant_count) {
      if (definitions_ == options_.constant_count + 1) {
        Error(index, DiagnosticCode::kTooManyDefinitions,
              fmt::format("more def instructions than the {} constant registers (--max-constants): every one "
                          "past that count redefines a register",
                          options_.constant_count));
      }
      return;
    }
    auto [earlier, first] = defined_at_.emplace(reg.index, index);
    if (!first) {
      Warning(index, DiagnosticCode::kDuplicateDefinition,
              fmt::format("c{} is defined again; this later value wins and the earlier def{} does nothing",
                          reg.index, LineOf(earlier->second)));
      earlier->second = index;
    }
  }

  // " (line N)" for an instruction with a source line, else "".
  std::string LineOf(int index) const {
    const SourceLoc loc = program_.LocOf(index);
    return loc.line > 0 ? fmt::format(" (line {})", loc.line) : "";
  }

  const Program& program_;
  const ValidatorOptions options_;
  const bool dx9_;
  Diagnostics diagnostics_;

  int first_executable_ = -1;
  int slots_ = 0;
  std::array<std::uint8_t, kTempRegisterCount> written_lanes_{};
  bool a0_written_ = false;
  std::uint8_t position_lanes_ = 0;
  int last_position_write_ = -1;
  std::array<int, kInputRegisterCount> declared_at_{};  // first dcl of each v#, or -1
  std::map<std::pair<int, int>, int> usage_declared_at_;
  int definitions_ = 0;
  std::map<int, int> defined_at_;  // the last def of each c#
};

}  // namespace

std::uint8_t ConsumedLanes(const OpcodeInfo& info, int operand, WriteMask dest_mask, Swizzle swizzle) {
  const std::uint8_t swizzled = NeededSwizzledLanes(info, operand, dest_mask);
  std::uint8_t lanes = 0;
  for (int lane = 0; lane < kLaneCount; ++lane) {
    if (swizzled & (1 << lane)) lanes |= static_cast<std::uint8_t>(1 << swizzle[lane]);
  }
  return lanes;
}

Diagnostics Validate(const Program& program, const ValidatorOptions& options) {
  assert(options.constant_count >= 1);
  if (VersionEnabled(program.version) && program.model() != ShaderModel::kVs11) {
    return ValidateLaterModel(program, options);
  }
  return Validator(program, options).Run();
}

}  // namespace vs11
