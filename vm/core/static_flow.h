// Static flow control resolved for one set of integer and boolean constants, as drivers do: a later
// model's program (vs_2_0 on) whose rep/loop counts and if/call conditions come from i# and b# only
// becomes straight-line code that the batch and jit engines run as vs_1_1 code with the later model's
// registers (semantics::kLaterModelStraightLine; vm/engines/static_flow_engine.h).
// The walk follows the reference engine's control rules (vm/engines/reference_flow.cc) exactly: loop
// counts clamped to [0, 255], the outer aL restored when a loop ends, calls beyond the model's depth
// skipped, each c#[aL + n] read as the static c#[k] of its iteration.
#pragma once

#include <algorithm>
#include <array>
#include <string_view>
#include <vector>

#include "vm/core/machine.h"

namespace vs11 {

// Loop and rep counts outside [0, 255] (the range the reference gives for i#.x) are clamped to it.
inline constexpr int kMaxLoopCount = 255;

// The most instructions (flow instructions included) a specialisation walks: D3DCAPS9's smallest
// MaxVShaderInstructionsExecuted (65535), the executed-instruction limit every vs_2_0 device offers.
inline constexpr int kMaxStaticFlowSteps = 65535;
// The most instructions the straight-line program may have: the jit compiles it whole, and its
// register allocation grows faster than linearly with the length.
inline constexpr int kMaxUnrolledInstructions = 4096;

// Where each block instruction's partner is, found once: if/ifc -> its else or endif, else -> endif,
// loop/rep -> endloop/endrep and back; and where each label is. kNoMatch for an unbalanced program
// (only an unvalidated one), which then ends at that instruction.
inline constexpr int kNoMatch = -1;
struct ControlTable {
  std::vector<int> partner;
  std::vector<int> label_at;  // by label number
};
ControlTable BuildControlTable(const Program& program);

// The later models' control rules, written once: the reference engine (vm/engines/reference_flow.cc)
// walks a program with it for each vertex, the specialiser below once per set of constants. The host
// decides the conditions and runs everything else:
//   bool Condition(const SourceOperand&);      // if b#/p0.c, callnz's second source, breakp: `!` applied
//   bool Comparison(const Instruction&);       // if_comp, break_comp
//   Vec4i Integer(int index);                  // i# of rep and loop
//   void Execute(const Instruction&);          // every instruction that is not flow control
// `aL` is the host's: the walk sets it as loops start, step and end.
template <class Host>
class FlowWalk {
 public:
  FlowWalk(const Program& program, const ControlTable& control, Host& host, int& aL)
      : program_(program), control_(control), host_(host), aL_(aL), call_depth_(Info(program.model()).call_depth) {}

  // Runs instruction `pc`; the next one to run, or -1 when the program is done.
  int Step(int pc) {
    const Instruction& instruction = program_.instructions[static_cast<std::size_t>(pc)];
    const int partner = control_.partner[static_cast<std::size_t>(pc)];
    switch (instruction.opcode) {
      case Opcode::kRet:
      case Opcode::kLabel: return Return();  // falling onto a label ends the routine, as ret does
      case Opcode::kCall: return Call(instruction.sources[0], pc);
      case Opcode::kCallnz: return host_.Condition(instruction.sources[1]) ? Call(instruction.sources[0], pc) : pc + 1;
      case Opcode::kIf: return host_.Condition(instruction.sources[0]) ? pc + 1 : Skip(partner);
      case Opcode::kIfc: return host_.Comparison(instruction) ? pc + 1 : Skip(partner);
      case Opcode::kElse: return Skip(partner);  // the if's branch ran: past the endif
      case Opcode::kEndif: return pc + 1;
      case Opcode::kRep:
      case Opcode::kLoop: return EnterLoop(instruction, pc, partner);
      case Opcode::kEndrep:
      case Opcode::kEndloop: return EndOfBody(pc);
      case Opcode::kBreak: return Break(pc);
      case Opcode::kBreakc: return host_.Comparison(instruction) ? Break(pc) : pc + 1;
      case Opcode::kBreakp: return host_.Condition(instruction.sources[0]) ? Break(pc) : pc + 1;
      default: host_.Execute(instruction); return pc + 1;
    }
  }

 private:
  struct LoopFrame {
    int first = 0;  // the body's first instruction
    int end = 0;    // the endloop or endrep
    int remaining = 0;
    int step = 0;
    int outer_aL = 0;  // restored when a loop ends: aL is the innermost loop's
    bool is_loop = false;
  };
  struct CallFrame {
    int return_to = 0;
    std::size_t loop_depth = 0;
  };

  // Past a block's closing instruction; an unmatched block ends the program.
  static int Skip(int partner) { return partner == kNoMatch ? -1 : partner + 1; }

  int Return() {
    if (calls_.empty()) return -1;  // the main program's ret
    const CallFrame frame = calls_.back();
    calls_.pop_back();
    loops_.resize(std::min(loops_.size(), frame.loop_depth));
    return frame.return_to;
  }

  // A call beyond the model's nesting (the validator rejects it; recursion included) is skipped, so
  // that an unvalidated program cannot recurse without end.
  int Call(const SourceOperand& label, int pc) {
    const int index = label.reg.index;
    const bool known = index >= 0 && index < static_cast<int>(control_.label_at.size()) &&
                       control_.label_at[static_cast<std::size_t>(index)] != kNoMatch;
    if (!known || static_cast<int>(calls_.size()) >= call_depth_) return pc + 1;
    calls_.push_back({pc + 1, loops_.size()});
    return control_.label_at[static_cast<std::size_t>(index)] + 1;
  }

  int EnterLoop(const Instruction& instruction, int pc, int partner) {
    const bool is_loop = instruction.opcode == Opcode::kLoop;
    const Vec4i counter = host_.Integer(instruction.sources[is_loop ? 1 : 0].reg.index);
    const int count = std::clamp(counter[0], 0, kMaxLoopCount);
    if (count == 0 || partner == kNoMatch) return Skip(partner);
    loops_.push_back({pc + 1, partner, count, counter[2], aL_, is_loop});
    if (is_loop) aL_ = counter[1];
    return pc + 1;
  }

  int EndOfBody(int pc) {
    if (loops_.empty() || loops_.back().end != pc) return pc + 1;  // only an unvalidated program
    LoopFrame& frame = loops_.back();
    if (frame.is_loop) aL_ += frame.step;
    if (--frame.remaining > 0) return frame.first;
    Leave();
    return pc + 1;
  }

  int Break(int pc) {
    if (loops_.empty()) return pc + 1;
    const int end = loops_.back().end;
    Leave();
    return end + 1;
  }

  void Leave() {
    if (loops_.back().is_loop) aL_ = loops_.back().outer_aL;
    loops_.pop_back();
  }

  const Program& program_;
  const ControlTable& control_;
  Host& host_;
  int& aL_;
  const int call_depth_;
  std::vector<LoopFrame> loops_;
  std::vector<CallFrame> calls_;
};

// What a specialisation depends on: the integer and boolean constants after defi/defb.
struct StaticFlowKey {
  std::array<Vec4i, kIntegerConstantCount> integers{};
  std::array<bool, kBooleanConstantCount> booleans{};
  int constant_count = 0;  // the bank's size: a static c# past it reads 0
  friend bool operator==(const StaticFlowKey&, const StaticFlowKey&) = default;
};
StaticFlowKey StaticFlowKeyOf(const ConstantBank& constants);  // constants: ModelConstants'

// Success, or why `engine` cannot run `program` (a later model) specialised, whatever the constants:
// dynamic flow control (if_comp, break_comp, breakp, setp, predicated instructions, if/callnz on p0)
// and texldl. The later arithmetic rows, _sat, _abs, a0's four lanes and r0-r31 all run
// (semantics::kLaterModelStraightLine).
Status StaticFlowRefusal(const Program& program, std::string_view engine);

// `program` (which passes StaticFlowRefusal) as a straight-line program for the constants `key` (its
// version semantics::kLaterModelStraightLine: read as vs_1_1, with r0-r31 and a0's lanes), or why not
// (the walk exceeds kMaxStaticFlowSteps or the result kMaxUnrolledInstructions). Its constants are
// the later model's bank: run it with ModelConstants(program, api_constants). It has no dcl or def.
Result<Program> SpecialiseStaticFlow(const Program& program, const StaticFlowKey& key, std::string_view engine);

// The bank a later model's program sees: at least the model's constants (vs_2_0 on: 256, which the
// validator lets a program read whatever the API bank's size), its definitions written over the API's
// values.
ConstantBank ModelConstants(const Program& program, ConstantBank api_constants);

}  // namespace vs11
