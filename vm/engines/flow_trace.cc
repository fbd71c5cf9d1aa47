#include "vm/engines/flow_trace.h"

#include <algorithm>

#include <fmt/format.h>

#include "vm/core/operands.h"
#include "vm/engines/reference_flow.h"

namespace vs11 {
namespace {

Vec4f Bools(const std::array<bool, 4>& lanes) {
  return {lanes[0] ? 1.0f : 0.0f, lanes[1] ? 1.0f : 0.0f, lanes[2] ? 1.0f : 0.0f, lanes[3] ? 1.0f : 0.0f};
}

TracedRead ReadOf(int source, const RegisterRef& reg) {
  TracedRead read;
  read.source = source;
  read.register_read = reg;
  return read;
}

// "aL = 4", "a0.y = 2": what a relative operand was read through.
std::string AddressNote(const RegisterRef& reg, const FlowState& state) {
  if (reg.address.file == RegisterFile::kLoop) return fmt::format("aL = {}", state.aL);
  const int lane = reg.address.swizzle_bits & 3;
  return fmt::format("a0.{} = {}", kLaneLetters[lane], state.a0[static_cast<std::size_t>(lane)]);
}

// Records each instruction the walk runs: its reads before, its write and what it decided after.
class FlowTraceRecorder final : public FlowObserver {
 public:
  FlowTraceRecorder(const Program& program, const ConstantBank& constants, std::vector<TraceStep>& steps)
      : program_(program), constants_(constants), declared_(DeclaredOutputSlots(program)), steps_(steps) {}

  void Before(int index, const FlowState& state) override {
    const Instruction& instruction = program_.instructions[static_cast<std::size_t>(index)];
    const OpcodeInfo& info = instruction.info();
    if (!info.is_executable()) return;
    TraceStep step;
    step.instruction_index = index;
    for (int s = 0; s < std::min(SourceCount(info, program_.model()), 3); ++s) {
      const SourceOperand& source = instruction.sources[s];
      switch (source.reg.file) {
        case RegisterFile::kLabel:
        case RegisterFile::kLoop: break;  // call's target, loop's aL: named by the note
        case RegisterFile::kConstBool:
        case RegisterFile::kPredicate: step.reads.push_back(ConditionRead(s, source, state)); break;
        case RegisterFile::kConstInt: {
          const Vec4i value = constants_.ReadInteger(source.reg.index);
          TracedRead read = ReadOf(s, source.reg);
          for (int lane = 0; lane < 4; ++lane) read.raw[lane] = static_cast<float>(value[static_cast<std::size_t>(lane)]);
          read.value = read.raw;
          step.reads.push_back(read);
          break;
        }
        default:
          for (int row = 0; row < info.registers_read(s); ++row) step.reads.push_back(ValueRead(s, row, source, state));
      }
    }
    if (instruction.predicated) {
      TracedRead read = ReadOf(TracedRead::kPredicateOperand, instruction.predicate.reg);
      read.raw = Bools(state.p0);
      for (int lane = 0; lane < 4; ++lane) read.value[lane] = FlowPredicateLane(instruction, lane, state) ? 1.0f : 0.0f;
      read.boolean = true;
      step.reads.push_back(read);
    }
    if (info.kind != ResultKind::kNoResult) {
      const WriteMask lanes = semantics::LanesWritten(instruction);
      std::uint8_t on = lanes.bits(), off = 0;
      for (int lane = 0; lane < 4 && instruction.predicated; ++lane) {
        if (lanes.has(lane) && !FlowPredicateLane(instruction, lane, state)) {
          on &= static_cast<std::uint8_t>(~(1u << lane));
          off |= static_cast<std::uint8_t>(1u << lane);
        }
      }
      step.write = TracedWrite{WriteMask(on), Destination(instruction.dest.reg, state), {}, WriteMask(off)};
    }
    steps_.push_back(std::move(step));
  }

  void After(int index, int next, const FlowState& state) override {
    if (steps_.empty() || steps_.back().instruction_index != index) return;
    TraceStep& step = steps_.back();
    const Instruction& instruction = program_.instructions[static_cast<std::size_t>(index)];
    if (step.write) step.write->after = Destination(instruction.dest.reg, state);
    step.note = FlowNote(instruction, index, next, state);
  }

 private:
  TracedRead ValueRead(int s, int row, const SourceOperand& source, const FlowState& state) const {
    TracedRead read;
    read.source = s;
    read.row = row;
    read.register_read = source.reg;
    read.register_read.index = static_cast<int>(FlowAddress(source.reg, state)) + row;
    read.register_read.relative = false;
    read.raw = FlowReadRegister(source.reg, row, constants_, state);
    read.value = FlowFetch(source, row, constants_, state);
    if (source.reg.relative) read.address = AddressNote(source.reg, state);
    return read;
  }

  // b# or p0.c as a condition: the value, `!` applied, in every lane; raw: b# or p0's four lanes.
  TracedRead ConditionRead(int s, const SourceOperand& source, const FlowState& state) const {
    TracedRead read = ReadOf(s, source.reg);
    read.raw = source.reg.file == RegisterFile::kPredicate ? Bools(state.p0)
                                                           : Bools({constants_.ReadBoolean(source.reg.index), false, false, false});
    read.value.fill(FlowCondition(source, constants_, state) ? 1.0f : 0.0f);
    read.boolean = true;
    return read;
  }

  // A destination's value: a0's lanes as integers, p0's as 1 or 0, a temporary or output.
  Vec4f Destination(const RegisterRef& reg, const FlowState& state) const {
    if (reg.file == RegisterFile::kAddress) {
      Vec4f lanes;
      for (int lane = 0; lane < 4; ++lane) lanes[lane] = static_cast<float>(state.a0[static_cast<std::size_t>(lane)]);
      return lanes;
    }
    if (reg.file == RegisterFile::kPredicate) return Bools(state.p0);
    const Vec4f* target = FlowTarget(reg, program_.model(), declared_, state);
    return target != nullptr ? *target : Vec4f{};
  }

  // "line 12" (where the program came from text), else "instruction 7".
  std::string Where(int index) const {
    if (index < 0) return "the end";
    const SourceLoc loc = program_.LocOf(index);
    return loc.line > 0 ? fmt::format("line {}", loc.line) : fmt::format("instruction {}", index);
  }

  std::string FlowNote(const Instruction& instruction, int index, int next, const FlowState& state) const {
    const bool falls_through = next == index + 1;
    switch (instruction.opcode) {
      case Opcode::kRep:
      case Opcode::kLoop: {
        if (!falls_through) return "no iteration: continues at " + Where(next);
        const bool is_loop = instruction.opcode == Opcode::kLoop;
        const Vec4i counter = constants_.ReadInteger(instruction.sources[is_loop ? 1 : 0].reg.index);
        const int count = std::clamp(counter[0], 0, kMaxLoopCount);
        std::string note = fmt::format("{} iteration{}", count, count == 1 ? "" : "s");
        if (is_loop) note += fmt::format(", aL = {}, step {}", state.aL, counter[2]);
        return note;
      }
      case Opcode::kEndrep:
      case Opcode::kEndloop:
        if (next >= 0 && next <= index) {
          return instruction.opcode == Opcode::kEndloop ? fmt::format("next iteration, aL = {}", state.aL) : "next iteration";
        }
        return "the loop ends";
      case Opcode::kIf:
      case Opcode::kIfc: return falls_through ? "true: runs the block" : "false: continues at " + Where(next);
      case Opcode::kElse: return "the if block ran: continues at " + Where(next);
      case Opcode::kCall:
      case Opcode::kCallnz: {
        const std::string condition = instruction.opcode == Opcode::kCallnz ? (falls_through ? "false: " : "true: ") : "";
        if (falls_through) return condition + "no call";
        return fmt::format("{}calls l{} at {}", condition, instruction.sources[0].reg.index, Where(next));
      }
      case Opcode::kRet:
      case Opcode::kLabel: return next < 0 ? "the program ends" : "returns to " + Where(next);
      case Opcode::kBreak: return "leaves the loop: continues at " + Where(next);
      case Opcode::kBreakc:
      case Opcode::kBreakp:
        return falls_through ? "false: stays in the loop" : "true: leaves the loop, continues at " + Where(next);
      default: return "";
    }
  }

  const Program& program_;
  const ConstantBank& constants_;
  const std::array<std::optional<int>, kOutputRegisterCountVs30> declared_;
  std::vector<TraceStep>& steps_;
};

}  // namespace

VertexTrace TraceFlowVertex(const Program& program, const ConstantBank& api_constants, const VertexArrays& inputs,
                            std::size_t vertex, FloatRules rules) {
  VertexTrace trace;
  trace.vertex = vertex;
  trace.input_registers = inputs.registers();
  std::sort(trace.input_registers.begin(), trace.input_registers.end());
  const ConstantBank constants = ModelConstants(program, api_constants);
  FlowState state;
  StartFlowVertex(inputs, vertex, WrittenOutputLanes(program), state);
  static_assert(std::tuple_size_v<decltype(state.inputs)> == std::tuple_size_v<decltype(trace.start.inputs)>);
  std::copy(state.inputs.begin(), state.inputs.end(), trace.start.inputs.begin());
  FlowTraceRecorder recorder(program, constants, trace.steps);
  RunFlowVertex(program, constants, state, &recorder, rules);
  trace.end.outputs = state.outputs;
  return trace;
}

}  // namespace vs11
