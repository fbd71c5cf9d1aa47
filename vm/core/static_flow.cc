#include "vm/core/static_flow.h"

#include <algorithm>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "vm/core/operands.h"

namespace vs11 {

bool OpensBlock(Opcode op) { return op == Opcode::kIf || op == Opcode::kIfc || op == Opcode::kLoop || op == Opcode::kRep; }
bool ClosesBlock(Opcode op) { return op == Opcode::kEndif || op == Opcode::kEndloop || op == Opcode::kEndrep; }

ControlTable BuildControlTable(const Program& program) {
  const int n = static_cast<int>(program.instructions.size());
  ControlTable table;
  table.partner.assign(static_cast<std::size_t>(n), kNoMatch);
  std::vector<int> open;  // indices of if/loop/rep, and of else in place of its if
  for (int i = 0; i < n; ++i) {
    const Instruction& instruction = program.instructions[static_cast<std::size_t>(i)];
    const Opcode op = instruction.opcode;
    if (op == Opcode::kLabel) {
      const int label = instruction.sources[0].reg.index;
      if (label >= 0 && label < RegisterCount(RegisterFile::kLabel, ShaderModel::kVs30)) {
        if (static_cast<int>(table.label_at.size()) <= label) table.label_at.resize(static_cast<std::size_t>(label) + 1, kNoMatch);
        table.label_at[static_cast<std::size_t>(label)] = i;
      }
      open.clear();  // a subroutine starts afresh
    } else if (OpensBlock(op)) {
      open.push_back(i);
    } else if (op == Opcode::kElse && !open.empty()) {
      table.partner[static_cast<std::size_t>(open.back())] = i;
      open.back() = i;
    } else if (ClosesBlock(op) && !open.empty()) {
      table.partner[static_cast<std::size_t>(open.back())] = i;
      if (op != Opcode::kEndif) table.partner[static_cast<std::size_t>(i)] = open.back();
      open.pop_back();
    }
  }
  return table;
}

StaticFlowKey StaticFlowKeyOf(const ConstantBank& constants) {
  StaticFlowKey key;
  for (int i = 0; i < kIntegerConstantCount; ++i) key.integers[static_cast<std::size_t>(i)] = constants.ReadInteger(i);
  for (int i = 0; i < kBooleanConstantCount; ++i) key.booleans[static_cast<std::size_t>(i)] = constants.ReadBoolean(i);
  key.constant_count = constants.size();
  return key;
}

ConstantBank ModelConstants(const Program& program, ConstantBank api_constants) {
  api_constants.GrowTo(RegisterCount(RegisterFile::kConst, program.model()));
  return ApplyDefinitions(program, std::move(api_constants));
}

namespace {

// Where a read that the reference engine gives 0 (an input or constant past its file, a temporary
// past r31) points in the straight-line program: a constant far below c0, which every engine reads as 0
// with all the rows of a matrix.
constexpr int kZeroRow = -(1 << 20);

Diagnostic Refuse(const Program& program, std::size_t i, std::string_view engine, std::string_view why) {
  const SourceLoc loc = program.LocOf(static_cast<int>(i));
  return Failure(DiagnosticCode::kEngineUnavailable,
                 fmt::format("the {} engine cannot run this {} program (instruction {}{}, {}): {}", engine,
                             ShaderModelName(program.model()), i + 1,
                             loc.line > 0 ? fmt::format(", line {}", loc.line) : "",
                             program.instructions[i].info().mnemonic, why),
                 loc);
}

constexpr std::string_view kDynamicFlow =
    "dynamic flow control runs on the ref engine only (batch and jit resolve static flow: rep and loop on i#, "
    "if and callnz on b#)";

std::optional<std::string> RefusalOf(const Instruction& instruction) {
  const Opcode op = instruction.opcode;
  if (op == Opcode::kIfc || op == Opcode::kBreakc || op == Opcode::kBreakp || op == Opcode::kSetp ||
      instruction.predicated) {
    return std::string(kDynamicFlow);
  }
  if ((op == Opcode::kIf || op == Opcode::kCallnz) &&
      instruction.sources[op == Opcode::kIf ? 0 : 1].reg.file == RegisterFile::kPredicate) {
    return std::string(kDynamicFlow);
  }
  return std::nullopt;  // texldl is refused before (LaterModelRefusal); every other row has a kernel
}

RegisterRef RegisterOfSlot(int slot) {
  if (slot < static_cast<int>(OutputSlot::kDiffuse)) return {RegisterFile::kRasterOut, slot};
  if (slot < static_cast<int>(OutputSlot::kTexCoord0)) {
    return {RegisterFile::kAttributeOut, slot - static_cast<int>(OutputSlot::kDiffuse)};
  }
  return {RegisterFile::kTexCoordOut, slot - static_cast<int>(OutputSlot::kTexCoord0)};
}

// The reference engine's control walk (vm/engines/reference_flow.cc) with every condition a constant:
// the instructions it would run, in order, each with aL resolved.
class Specialiser {
 public:
  Specialiser(const Program& program, const StaticFlowKey& key)
      : program_(program), control_(BuildControlTable(program)), key_(key),
        declared_outputs_(DeclaredOutputSlots(program)) {
    out_.version = semantics::kLaterModelStraightLine;
  }

  Result<Program> Run(std::string_view engine) {
    const int n = static_cast<int>(program_.instructions.size());
    int steps = 0;
    FlowWalk<Specialiser> walk(program_, control_, *this, aL_);
    for (int pc = 0; pc >= 0 && pc < n; pc = walk.Step(pc)) {
      if (++steps > kMaxStaticFlowSteps) {
        return Failure(DiagnosticCode::kEngineUnavailable,
                       fmt::format("the {} engine cannot specialise this {} program for its integer and boolean "
                                   "constants: it runs more than {} instructions (D3D9's smallest "
                                   "MaxVShaderInstructionsExecuted); the ref engine runs it",
                                   engine, ShaderModelName(program_.model()), kMaxStaticFlowSteps));
      }
      if (static_cast<int>(out_.instructions.size()) > kMaxUnrolledInstructions) {
        return Failure(DiagnosticCode::kEngineUnavailable,
                       fmt::format("the {} engine cannot specialise this {} program for its integer and boolean "
                                   "constants: unrolled it has more than {} instructions, the most the engine "
                                   "compiles; the ref engine runs it",
                                   engine, ShaderModelName(program_.model()), kMaxUnrolledInstructions));
      }
    }
    return std::move(out_);
  }

 private:
  friend class FlowWalk<Specialiser>;

  Vec4i Integer(int index) const {
    return index >= 0 && index < kIntegerConstantCount ? key_.integers[static_cast<std::size_t>(index)] : Vec4i{};
  }
  static bool Comparison(const Instruction&) { return false; }  // StaticFlowRefusal keeps if_comp out

  bool Condition(const SourceOperand& source) const {
    const int index = source.reg.index;
    const bool value = source.reg.file == RegisterFile::kConstBool && index >= 0 && index < kBooleanConstantCount &&
                       key_.booleans[static_cast<std::size_t>(index)];
    return value != source.logical_not;
  }

  // The static register a source reads on this iteration; kZeroRow where the reference reads 0.
  RegisterRef Resolve(RegisterRef reg, int rows) const {
    if (reg.relative && reg.address.file == RegisterFile::kLoop) {
      // aL + n in the reference engine's long arithmetic.
      const long index = static_cast<long>(reg.index) + aL_;
      reg = RegisterRef{reg.file, index < kZeroRow || index > key_.constant_count ? kZeroRow : static_cast<int>(index)};
    }
    if (reg.file == RegisterFile::kConst && !reg.relative && (reg.index < 0 || reg.index >= key_.constant_count)) {
      return {RegisterFile::kConst, kZeroRow};  // a matrix's later rows past the bank read 0 as well
    }
    if (reg.file == RegisterFile::kInput && (reg.index < 0 || reg.index + rows > kInputRegisterCount)) {
      return {RegisterFile::kConst, kZeroRow};  // (a matrix of inputs past v15 is not a valid program)
    }
    return reg;
  }

  void Execute(const Instruction& instruction) {
    const OpcodeInfo& info = instruction.info();
    if (!info.is_executable()) return;  // dcl, def, defi, defb: the bank and the outputs are the engine's
    Instruction out = instruction;
    for (int s = 0; s < info.source_count(); ++s) {
      out.sources[static_cast<std::size_t>(s)].reg = Resolve(instruction.sources[static_cast<std::size_t>(s)].reg, info.registers_read(s));
    }
    RegisterRef& dest = out.dest.reg;
    if (program_.model() == ShaderModel::kVs30 && dest.file == RegisterFile::kTexCoordOut) {
      const long index = dest.index + (dest.relative ? static_cast<long>(aL_) : 0);
      if (index < 0 || index >= kOutputRegisterCountVs30) return;  // the reference writes nothing
      const std::optional<int> slot = declared_outputs_[static_cast<std::size_t>(index)];
      if (!slot) return;
      dest = RegisterOfSlot(*slot);
    }
    out_.instructions.push_back(out);
  }

  const Program& program_;
  const ControlTable control_;
  const StaticFlowKey& key_;
  const std::array<std::optional<int>, kOutputRegisterCountVs30> declared_outputs_;
  Program out_;
  int aL_ = 0;
};

}  // namespace

Status StaticFlowRefusal(const Program& program, std::string_view engine) {
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    if (std::optional<std::string> why = RefusalOf(program.instructions[i])) return Refuse(program, i, engine, *why);
  }
  return {};
}

Result<Program> SpecialiseStaticFlow(const Program& program, const StaticFlowKey& key, std::string_view engine) {
  return Specialiser(program, key).Run(engine);
}

}  // namespace vs11
