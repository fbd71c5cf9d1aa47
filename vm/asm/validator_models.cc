// The validator's rules for vs_2_0, vs_2_x and vs_3_0 (vm/asm/validator.h): register counts, slot and
// nesting limits of each model (vm/core/shader_model.h), the structure of flow control, labels and
// subroutines, the operands each later instruction takes, the read ports and reads per instruction of
// each register type (vm/asm/read_ports.h, shared with vs_1_1) and reads of unwritten temporaries along the flow control
// (vm/asm/temporary_dataflow.h). vs_1_1's rules are in validator.cc.
// Operand rules from the D3D9 asm reference's instruction pages ("- vs"): crs writes no w; sincos writes
// .x, .y or .xy; pow's sources are single components; sgn's src1 and src2 are two different temporaries;
// nrm writes a temporary that is not its source; mova writes a0, with any mask in every later model (the
// mova page: "for versions 2_x and above, the address register is a component vector, therefore any write
// mask is allowed"; we read "2_x" as the 2.x family, as Microsoft's assembler takes `mova a0.y` in
// vs_2_0: Wine's case 20); if_comp's and break_comp's sources, and the p0 of if, callnz and breakp, are
// one component (a replicate swizzle), a predicate p0 lane for lane or one lane. Reads of a0 and p0
// before mova and setp write them are followed along the flow control with the temporaries
// (vm/asm/temporary_dataflow.h). Not modelled yet: sincos's vs_2_0 constant operands being c#.
#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "vm/asm/disassembler.h"
#include "vm/asm/lexer.h"
#include "vm/asm/read_ports.h"
#include "vm/asm/temporary_dataflow.h"
#include "vm/asm/validator.h"

namespace vs11 {
namespace {

// The blocks flow control opens, with the kind of nesting each counts against.
enum class Block { kIfStatic, kIfDynamic, kLoop, kRep };

struct OpenBlock {
  Block kind;
  int index;  // the opening instruction
  bool has_else = false;
};

class LaterModelValidator {
 public:
  LaterModelValidator(const Program& program, const ValidatorOptions& options)
      : program_(program), options_(options), model_(program.model()), limits_(Info(program.model())) {}

  Diagnostics Run() {
    for (int i = 0; i < static_cast<int>(program_.instructions.size()); ++i) {
      const Instruction& instruction = program_.instructions[i];
      if (!OpcodeAllowed(instruction.info(), model_)) {
        Error(i, DiagnosticCode::kUnknownInstruction,
              fmt::format("is not a {} instruction (it exists from {} on)", limits_.name,
                          ShaderModelName(instruction.info().since)));
        continue;
      }
      CountSlots(i);
      CheckOperands(i);
      CheckFlowControl(i);
      RecordUse(i);
    }
    for (const OpenBlock& block : open_) {
      Error(block.index, DiagnosticCode::kUnmatchedFlowControl,
            fmt::format("is not closed (expected {})", Closer(block.kind)));
    }
    CheckLabels();
    for (const TemporaryReadFinding& finding : FindUnwrittenTemporaryReads(program_)) {
      Report(finding.index, finding.severity, finding.code, finding.message);
    }
    CheckInputsDeclared();
    if (options_.require_position) CheckPosition();
    return std::move(diagnostics_);
  }

 private:
  const Instruction& At(int index) const { return program_.instructions[index]; }

  void Error(int index, DiagnosticCode code, std::string_view message) { Report(index, Severity::kError, code, message); }
  void Report(int index, Severity severity, DiagnosticCode code, std::string_view message) {
    const SourceLoc loc = program_.LocOf(index);
    const std::string subject = loc.line > 0 ? FormatInstruction(At(index), Syntax::kDx9, model_)
                                             : fmt::format("instruction {} ({})", index, At(index).info().mnemonic);
    diagnostics_.Add(Diagnostic{loc, severity, code, fmt::format("{}: {}", subject, message),
                                program_.WordOffsetOf(index)});
  }
  SourceLoc ProgramLoc() const {
    return program_.source_locs.empty() ? SourceLoc{} : SourceLoc{program_.source_locs.front().file, 0, 0};
  }
  std::string Name(const RegisterRef& reg) const { return RegisterName(reg.file, reg.index, model_); }

  void CountSlots(int index) {
    const int before = slots_;
    slots_ += At(index).info().is_executable() ? At(index).info().slots : 0;
    if (before <= limits_.instruction_slots && slots_ > limits_.instruction_slots) {
      Error(index, DiagnosticCode::kTooManySlots,
            fmt::format("takes the program to {} instruction slots, over the {} limit of {}", slots_, limits_.name,
                        limits_.instruction_slots));
    }
  }

  // --- operands --------------------------------------------------------------------------------

  // The register exists in the model (constants: in the device's bank; relative: the offset).
  bool CheckExists(int index, const RegisterRef& reg, std::string_view what) {
    const int count = reg.file == RegisterFile::kConst
                          ? std::max(options_.constant_count, RegisterCount(RegisterFile::kConst, model_))
                          : RegisterCount(reg.file, model_);
    if (count == 0) {
      Error(index, DiagnosticCode::kNoSuchRegister,
            fmt::format("{} names {}, which {} does not have", what, Name(reg), limits_.name));
      return false;
    }
    if (reg.index < count || (reg.relative && reg.file != RegisterFile::kConst)) return true;
    Error(index, DiagnosticCode::kNoSuchRegister,
          fmt::format("{} names {}{}, outside the {} registers {} has", what, Name(reg),
                      reg.relative ? " (relative offset)" : "", count, limits_.name));
    return false;
  }

  void Expect(int index, bool ok, std::string_view what, std::string_view needs) {
    if (!ok) Error(index, DiagnosticCode::kBadOperand, fmt::format("{} must be {}", what, needs));
  }

  static bool IsFile(const SourceOperand& source, RegisterFile file) { return source.reg.file == file; }

  // A condition or comparison reads one lane: if_comp and break_comp compare two scalars, and if p0,
  // callnz l#, p0 and breakp test one predicate lane (the asm reference's pages for each: a replicate
  // swizzle is required; "[!]p0.c"). setp has no such rule: it compares lane by lane.
  void ExpectOneLane(int index, const SourceOperand& source, std::string_view what) {
    if (source.swizzle.is_replicate()) return;
    Error(index, DiagnosticCode::kScalarSwizzle,
          fmt::format("{} ({}) must be one component: give it a replicate swizzle such as .x", what,
                      FormatSource(source, Syntax::kDx9, model_)));
  }

  // What each later instruction's operands must be, and the files that may be read or written.
  void CheckOperands(int index) {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    const Opcode op = instruction.opcode;
    const int sources = SourceCount(info, model_);
    if (info.has_dest() && !CheckExists(index, instruction.dest.reg, "the destination")) return;
    for (int s = 0; s < sources; ++s) {
      if (!CheckExists(index, instruction.sources[s].reg, fmt::format("src{}", s))) return;
      const SourceOperand& source = instruction.sources[s];
      if (source.reg.relative) CheckRelative(index, source.reg);
      const bool condition = (op == Opcode::kIf && s == 0) || (op == Opcode::kCallnz && s == 1) ||
                             op == Opcode::kBreakp;
      if (source.logical_not && !condition) {
        Error(index, DiagnosticCode::kSourceModifier, fmt::format("src{}: '!' applies only to a condition", s));
      }
    }
    if (instruction.predicated && CheckExists(index, instruction.predicate.reg, "the predicate") &&
        !instruction.predicate.swizzle.is_identity() && !instruction.predicate.swizzle.is_replicate()) {
      // A predicate is p0 lane for lane (.xyzw, the default) or one lane for all (the asm reference's
      // predicate register page: "([!]p0[.swizzle])", a full or a replicate swizzle).
      Error(index, DiagnosticCode::kScalarSwizzle,
            fmt::format("the predicate ({}) must be p0 lane for lane (.xyzw) or one lane (a replicate swizzle "
                        "such as p0.x)",
                        FormatSource(instruction.predicate, Syntax::kDx9, model_)));
    }
    for (const ReadPortViolation& violation : FindReadPortViolations(instruction, model_)) {
      Error(index, DiagnosticCode::kReadPorts, DescribeReadPortViolation(violation, model_));
    }
    if (instruction.dest.reg.relative) CheckRelative(index, instruction.dest.reg);
    const SourceOperand& s0 = instruction.sources[0];
    const SourceOperand& s1 = instruction.sources[1];
    const RegisterFile dest = instruction.dest.reg.file;
    switch (op) {
      case Opcode::kRep: Expect(index, IsFile(s0, RegisterFile::kConstInt), "rep's count", "an integer constant i#"); return;
      case Opcode::kLoop:
        Expect(index, IsFile(s0, RegisterFile::kLoop), "loop's first operand", "aL");
        Expect(index, IsFile(s1, RegisterFile::kConstInt), "loop's second operand", "an integer constant i#");
        return;
      case Opcode::kIf:
        Expect(index, IsFile(s0, RegisterFile::kConstBool) || IsFile(s0, RegisterFile::kPredicate), "if's condition",
               RegisterCount(RegisterFile::kPredicate, model_) ? "b# or p0 with one component" : "a boolean constant b#");
        if (IsFile(s0, RegisterFile::kPredicate)) ExpectOneLane(index, s0, "if's condition");
        return;
      case Opcode::kIfc:
      case Opcode::kBreakc:
        ExpectOneLane(index, s0, op == Opcode::kIfc ? "if_comp's src0" : "break_comp's src0");
        ExpectOneLane(index, s1, op == Opcode::kIfc ? "if_comp's src1" : "break_comp's src1");
        return;
      case Opcode::kCall:
      case Opcode::kLabel: Expect(index, IsFile(s0, RegisterFile::kLabel), "the operand", "a label l#"); return;
      case Opcode::kCallnz:
        Expect(index, IsFile(s0, RegisterFile::kLabel), "callnz's target", "a label l#");
        Expect(index, IsFile(s1, RegisterFile::kConstBool) || IsFile(s1, RegisterFile::kPredicate),
               "callnz's condition", "b# or p0");
        if (IsFile(s1, RegisterFile::kPredicate)) ExpectOneLane(index, s1, "callnz's condition");
        return;
      case Opcode::kBreakp:
        Expect(index, IsFile(s0, RegisterFile::kPredicate), "breakp's operand", "p0");
        ExpectOneLane(index, s0, "breakp's operand");
        return;
      case Opcode::kSetp: Expect(index, dest == RegisterFile::kPredicate, "setp's destination", "p0"); break;
      case Opcode::kMova: Expect(index, dest == RegisterFile::kAddress, "mova's destination", "a0"); break;
      case Opcode::kTexldl: Expect(index, IsFile(s1, RegisterFile::kSampler), "texldl's src1", "a sampler s#"); break;
      case Opcode::kCrs:
        Expect(index, !instruction.dest.mask.has(3), "crs's write mask", "a subset of .xyz (w is not written)");
        break;
      case Opcode::kSincos: {
        const std::uint8_t mask = instruction.dest.mask.bits();
        Expect(index, mask >= 1 && mask <= 3, "sincos's write mask", ".x, .y or .xy");
        break;
      }
      case Opcode::kPow:
        Expect(index, s0.swizzle.is_replicate() && s1.swizzle.is_replicate(), "pow's sources",
               "single components (a replicate swizzle such as .x)");
        break;
      case Opcode::kSgn: {
        // D3D9 reference, sgn - vs: src1 and src2 are scratch space whose contents are undefined afterwards.
        const SourceOperand& s2 = instruction.sources[2];
        Expect(index, IsFile(s1, RegisterFile::kTemp) && IsFile(s2, RegisterFile::kTemp) && !s1.reg.relative &&
                          !s2.reg.relative && s1.reg.index != s2.reg.index,
               "sgn's src1 and src2", "two different temporaries r# (the reference page: their contents are "
               "undefined after sgn)");
        break;
      }
      case Opcode::kNrm:
        // D3D9 reference, nrm - vs: "dest must be a temporary register", and dest and src not the same.
        Expect(index, dest == RegisterFile::kTemp, "nrm's destination", "a temporary r# (the reference page's rule)");
        Expect(index, !(dest == s0.reg.file && instruction.dest.reg.index == s0.reg.index && !s0.reg.relative),
               "nrm's destination", "a different register from its source (the reference page's rule)");
        break;
      case Opcode::kDcl: CheckDeclaration(index); return;
      case Opcode::kDefi:
        Expect(index, dest == RegisterFile::kConstInt && !instruction.dest.reg.relative, "defi's register", "i#");
        return;
      case Opcode::kDefb:
        Expect(index, dest == RegisterFile::kConstBool && !instruction.dest.reg.relative, "defb's register", "b#");
        return;
      case Opcode::kDef:
        Expect(index, dest == RegisterFile::kConst && !instruction.dest.reg.relative, "def's register", "c#");
        return;
      default: break;
    }
    if (!info.has_dest() || !info.is_executable()) return;
    CheckDataOperands(index);
  }

  // Arithmetic: writes go to r#, outputs, a0 (mova) and p0 (setp); reads come from r#, v#, c#.
  void CheckDataOperands(int index) {
    const Instruction& instruction = At(index);
    const RegisterFile dest = instruction.dest.reg.file;
    const bool writable = dest == RegisterFile::kTemp || IsOutput(dest) ||
                          (dest == RegisterFile::kAddress && instruction.opcode == Opcode::kMova) ||
                          (dest == RegisterFile::kPredicate && instruction.opcode == Opcode::kSetp);
    if (!writable) {
      Error(index, DiagnosticCode::kReadOnlyDestination,
            fmt::format("cannot write {}{}", Name(instruction.dest.reg),
                        dest == RegisterFile::kAddress ? " with this instruction (a0 is written by mova)" : ""));
    }
    for (int s = 0; s < SourceCount(instruction.info(), model_); ++s) {
      const RegisterFile file = instruction.sources[s].reg.file;
      const bool readable = file == RegisterFile::kTemp || file == RegisterFile::kInput || file == RegisterFile::kConst ||
                            (file == RegisterFile::kSampler && instruction.opcode == Opcode::kTexldl && s == 1);
      if (!readable) {
        Error(index, DiagnosticCode::kWriteOnlySource,
              fmt::format("src{} reads {}, which an arithmetic instruction cannot read", s,
                          Name(instruction.sources[s].reg)));
      }
    }
  }

  // Constants are indexed by a0 or aL; inputs and outputs (vs_3_0) by aL only; one lane of a0.
  void CheckRelative(int index, const RegisterRef& reg) {
    const bool by_loop = reg.address.file == RegisterFile::kLoop;
    if (reg.file != RegisterFile::kConst && !by_loop) {
      Error(index, DiagnosticCode::kRelativeAddressing,
            fmt::format("{} can be indexed by aL only, not a0", Name(reg)));
    }
    if (!by_loop && !Swizzle(reg.address.swizzle_bits).is_replicate()) {
      Error(index, DiagnosticCode::kRelativeAddressing,
            fmt::format("{}'s index must be one lane of a0 (a0.x, a0.y, ...)", Name(reg)));
    }
    if (by_loop && loop_depth_ == 0 && in_main_) {
      Error(index, DiagnosticCode::kLoopRegisterOutsideLoop, "aL is used outside a loop/endloop block");
    }
  }

  void CheckDeclaration(int index) {
    const Instruction& instruction = At(index);
    const RegisterFile file = instruction.dest.reg.file;
    const bool ok = file == RegisterFile::kInput || file == RegisterFile::kSampler ||
                    (file == RegisterFile::kTexCoordOut && model_ >= ShaderModel::kVs30);
    Expect(index, ok, "dcl's register",
           model_ >= ShaderModel::kVs30 ? "an input v#, an output o# or a sampler s#" : "an input v#");
    if (file == RegisterFile::kInput) declared_inputs_.insert(instruction.dest.reg.index);
    if (file == RegisterFile::kTexCoordOut && instruction.usage == 0) declares_position_ = true;
  }

  // --- flow control ----------------------------------------------------------------------------

  static std::string_view Closer(Block kind) {
    switch (kind) {
      case Block::kLoop: return "endloop";
      case Block::kRep: return "endrep";
      default: return "endif";
    }
  }

  int Depth(Block kind) const {
    return static_cast<int>(std::count_if(open_.begin(), open_.end(), [&](const OpenBlock& b) {
      return kind == Block::kLoop ? b.kind == Block::kLoop || b.kind == Block::kRep : b.kind == kind;
    }));
  }

  void Open(int index, Block kind) {
    open_.push_back(OpenBlock{kind, index});
    const Block counted = kind == Block::kRep ? Block::kLoop : kind;
    const int limit = counted == Block::kLoop        ? limits_.loop_depth
                      : counted == Block::kIfStatic ? limits_.static_flow_depth
                                                    : limits_.dynamic_flow_depth;
    if (Depth(counted) > limit) {
      Error(index, DiagnosticCode::kNestingTooDeep,
            fmt::format("nests {} deep, over {}'s limit of {} for {}", Depth(counted), limits_.name, limit,
                        counted == Block::kLoop ? "loop and rep" : counted == Block::kIfStatic
                                                                        ? "static flow control (if b#)"
                                                                        : "dynamic flow control"));
    }
    if (kind == Block::kLoop) ++loop_depth_;
  }

  // Closes the innermost block, which must be one of `kinds`.
  void Close(int index, std::initializer_list<Block> kinds, std::string_view opener) {
    if (open_.empty() || std::find(kinds.begin(), kinds.end(), open_.back().kind) == kinds.end()) {
      Error(index, DiagnosticCode::kUnmatchedFlowControl,
            open_.empty() ? fmt::format("has no matching {}", opener)
                          : fmt::format("does not match the open {} (expected {})", At(open_.back().index).info().mnemonic,
                                        Closer(open_.back().kind)));
      return;
    }
    if (open_.back().kind == Block::kLoop) --loop_depth_;
    open_.pop_back();
  }

  void CheckFlowControl(int index) {
    const Instruction& instruction = At(index);
    const SourceOperand& s0 = instruction.sources[0];
    switch (instruction.opcode) {
      case Opcode::kIf: Open(index, IsFile(s0, RegisterFile::kPredicate) ? Block::kIfDynamic : Block::kIfStatic); break;
      case Opcode::kIfc: Open(index, Block::kIfDynamic); break;
      case Opcode::kLoop: Open(index, Block::kLoop); break;
      case Opcode::kRep: Open(index, Block::kRep); break;
      case Opcode::kEndloop: Close(index, {Block::kLoop}, "loop"); break;
      case Opcode::kEndrep: Close(index, {Block::kRep}, "rep"); break;
      case Opcode::kEndif: Close(index, {Block::kIfStatic, Block::kIfDynamic}, "if"); break;
      case Opcode::kElse:
        if (open_.empty() || open_.back().kind == Block::kLoop || open_.back().kind == Block::kRep ||
            open_.back().has_else) {
          Error(index, DiagnosticCode::kUnmatchedFlowControl, "has no open if block to belong to");
        } else {
          open_.back().has_else = true;
        }
        break;
      case Opcode::kBreak:
      case Opcode::kBreakc:
      case Opcode::kBreakp:
        if (Depth(Block::kLoop) == 0) {
          Error(index, DiagnosticCode::kUnmatchedFlowControl, "is not inside a loop or rep block");
        }
        break;
      case Opcode::kLabel: {
        if (!open_.empty()) {
          Error(index, DiagnosticCode::kUnmatchedFlowControl, "cannot be inside an if, loop or rep block");
        }
        if (!labels_.emplace(s0.reg.index, index).second) {
          Error(index, DiagnosticCode::kDuplicateLabel, fmt::format("l{} is defined twice", s0.reg.index));
        }
        in_main_ = false;
        current_label_ = s0.reg.index;
        break;
      }
      case Opcode::kRet:
        if (!open_.empty()) {
          Error(index, DiagnosticCode::kUnmatchedFlowControl,
                fmt::format("cannot be inside an open {} block (ret ends the main program or a subroutine)",
                            At(open_.back().index).info().mnemonic));
        }
        break;
      case Opcode::kCall:
      case Opcode::kCallnz: calls_.push_back({current_label_, s0.reg.index, index}); break;
      default: break;
    }
  }

  void RecordUse(int index) {
    const Instruction& instruction = At(index);
    if (instruction.dest.reg.file == RegisterFile::kRasterOut && instruction.dest.reg.index == 0 &&
        instruction.info().is_executable()) {
      writes_position_ = true;
    }
    for (int s = 0; s < SourceCount(instruction.info(), model_); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file == RegisterFile::kInput && !reg.relative && instruction.opcode != Opcode::kDcl) {
        input_reads_.emplace(reg.index, index);
      }
    }
  }

  // Every call has a label; calls nest at most call_depth deep and never recurse.
  void CheckLabels() {
    for (const Call& call : calls_) {
      if (!labels_.count(call.target)) {
        Error(call.index, DiagnosticCode::kUndefinedLabel, fmt::format("calls l{}, which no label defines", call.target));
      }
    }
    std::set<int> visiting;
    CheckCallDepth(kMainProgram, 0, visiting);
  }

  void CheckCallDepth(int caller, int depth, std::set<int>& visiting) {
    for (const Call& call : calls_) {
      if (call.caller != caller || !labels_.count(call.target)) continue;
      if (visiting.count(call.target) || depth + 1 > limits_.call_depth) {
        Error(call.index, DiagnosticCode::kNestingTooDeep,
              visiting.count(call.target)
                  ? fmt::format("calls l{} recursively", call.target)
                  : fmt::format("nests calls {} deep, over {}'s limit of {}", depth + 1, limits_.name, limits_.call_depth));
        continue;
      }
      visiting.insert(call.target);
      CheckCallDepth(call.target, depth + 1, visiting);
      visiting.erase(call.target);
    }
  }

  // D3D9 rules from vs_2_0 on: every v# read is declared.
  void CheckInputsDeclared() {
    for (const auto& [reg, index] : input_reads_) {
      if (!declared_inputs_.count(reg)) {
        Error(index, DiagnosticCode::kUndeclaredInput, fmt::format("reads v{}, which no dcl declares", reg));
      }
    }
  }

  // vs_2_0/vs_2_x write oPos; vs_3_0 declares an output with dcl_position.
  void CheckPosition() {
    if (model_ >= ShaderModel::kVs30 ? declares_position_ : writes_position_) return;
    diagnostics_.Error(ProgramLoc(), DiagnosticCode::kPositionNotWritten,
                       model_ >= ShaderModel::kVs30 ? "no output is declared with dcl_position (vs_3_0 must declare one)"
                                                    : fmt::format("the program never writes oPos ({} must)", limits_.name));
  }

  static constexpr int kMainProgram = -1;
  struct Call {
    int caller;  // label number, or kMainProgram
    int target;
    int index;
  };

  const Program& program_;
  const ValidatorOptions& options_;
  ShaderModel model_;
  const ShaderModelInfo& limits_;
  Diagnostics diagnostics_;
  int slots_ = 0;
  std::vector<OpenBlock> open_;
  int loop_depth_ = 0;
  bool in_main_ = true;
  int current_label_ = kMainProgram;
  std::map<int, int> labels_;  // label number -> defining instruction
  std::vector<Call> calls_;
  std::set<int> declared_inputs_;
  std::map<int, int> input_reads_;  // v# -> first instruction reading it
  bool writes_position_ = false;
  bool declares_position_ = false;
};

}  // namespace

Diagnostics ValidateLaterModel(const Program& program, const ValidatorOptions& options) {
  return LaterModelValidator(program, options).Run();
}

}  // namespace vs11
