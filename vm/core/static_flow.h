// Static flow control resolved for one set of integer and boolean constants, as drivers do: a later
// model's program (vs_2_0 on) becomes straight-line code that the batch, jit and gl engines run as
// vs_1_1 code with the later model's registers (semantics::kLaterModelStraightLine;
// vm/engines/static_flow_engine.h): rep/loop counts and if/call on b# resolved, dynamic flow (if_comp,
// if p0, break_comp, breakp, callnz p0) as per-vertex execution masks.
// The walk follows the reference engine's control rules (vm/engines/reference_flow.cc) exactly: loop
// counts clamped to [0, 255], the outer aL restored when a loop ends, calls beyond the model's depth
// skipped, each c#[aL + n] read as the static c#[k] of its iteration.
#pragma once

#include <algorithm>
#include <array>
#include <string_view>
#include <type_traits>
#include <utility>
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

// How a condition turns out for the vertices a walk runs: for all of them alike, or per vertex.
enum class Branch : std::uint8_t { kNever, kAlways, kPerVertex };

// The later models' control rules, written once: the reference engine (vm/engines/reference_flow.cc)
// walks a program with it for each vertex, the specialiser below once per set of constants for all
// vertices at once. The host decides the conditions and runs everything else:
//   bool Condition(const SourceOperand&);      // if b#/p0.c, callnz's second source, breakp: `!` applied
//   bool Comparison(const Instruction&);       // if_comp, break_comp
//   Vec4i Integer(int index);                  // i# of rep and loop
//   void Execute(const Instruction&);          // every instruction that is not flow control
// `aL` is the host's: the walk sets it as loops start, step and end.
//
// A host that walks many vertices at once (the specialiser) returns Branch from Condition and
// Comparison. Where one is kPerVertex the walk takes both ways in turn and tells the host, which keeps
// the execution masks:
//   void BeginIf(const Instruction&); void Else(); void EndIf();    // an if whose branch is per vertex
//   bool BreakLanes(const Instruction&, Branch);  // break, breakc, breakp taken by some vertices (or
//                                                 // all): true when every running vertex leaves the loop
//   void EnterCall(const Instruction*);   // a call made; the callnz whose condition is per vertex
//   void Return();                        // ret, or a label reached: the routine (main included) ends
//   void LoopEntered(); void NextIteration(); void LoopLeft();
template <class Host>
class FlowWalk {
  static constexpr bool kPerVertex =
      std::is_same_v<decltype(std::declval<Host&>().Comparison(std::declval<const Instruction&>())), Branch>;
  static Branch Known(bool value) { return value ? Branch::kAlways : Branch::kNever; }
  static Branch Known(Branch value) { return value; }

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
      case Opcode::kCall: return Call(instruction, pc, Branch::kAlways);
      case Opcode::kCallnz: return Call(instruction, pc, Known(host_.Condition(instruction.sources[1])));
      case Opcode::kIf: return If(instruction, pc, partner, Known(host_.Condition(instruction.sources[0])));
      case Opcode::kIfc: return If(instruction, pc, partner, Known(host_.Comparison(instruction)));
      case Opcode::kElse:
        if constexpr (kPerVertex) {
          if (!open_ifs_.empty() && open_ifs_.back() == pc) {  // both branches run, each under its mask
            host_.Else();
            open_ifs_.back() = partner;
            return pc + 1;
          }
        }
        return Skip(partner);  // the if's branch ran: past the endif
      case Opcode::kEndif:
        if constexpr (kPerVertex) {
          if (!open_ifs_.empty() && open_ifs_.back() == pc) {
            host_.EndIf();
            open_ifs_.pop_back();
          }
        }
        return pc + 1;
      case Opcode::kRep:
      case Opcode::kLoop: return EnterLoop(instruction, pc, partner);
      case Opcode::kEndrep:
      case Opcode::kEndloop: return EndOfBody(pc);
      case Opcode::kBreak: return BreakIf(instruction, pc, Branch::kAlways);
      case Opcode::kBreakc: return BreakIf(instruction, pc, Known(host_.Comparison(instruction)));
      case Opcode::kBreakp: return BreakIf(instruction, pc, Known(host_.Condition(instruction.sources[0])));
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
    std::size_t if_depth = 0;
  };

  // Past a block's closing instruction; an unmatched block ends the program.
  static int Skip(int partner) { return partner == kNoMatch ? -1 : partner + 1; }

  int Return() {
    if constexpr (kPerVertex) host_.Return();
    if (calls_.empty()) return -1;  // the main program's ret
    const CallFrame frame = calls_.back();
    calls_.pop_back();
    loops_.resize(std::min(loops_.size(), frame.loop_depth));
    if constexpr (kPerVertex) open_ifs_.resize(std::min(open_ifs_.size(), frame.if_depth));
    return frame.return_to;
  }

  // A call beyond the model's nesting (the validator rejects it; recursion included) is skipped, so
  // that an unvalidated program cannot recurse without end.
  int Call(const Instruction& instruction, int pc, Branch branch) {
    const int index = instruction.sources[0].reg.index;
    const bool known = index >= 0 && index < static_cast<int>(control_.label_at.size()) &&
                       control_.label_at[static_cast<std::size_t>(index)] != kNoMatch;
    if (branch == Branch::kNever || !known || static_cast<int>(calls_.size()) >= call_depth_) return pc + 1;
    if constexpr (kPerVertex) host_.EnterCall(branch == Branch::kPerVertex ? &instruction : nullptr);
    calls_.push_back({pc + 1, loops_.size(), open_ifs_.size()});
    return control_.label_at[static_cast<std::size_t>(index)] + 1;
  }

  int If(const Instruction& instruction, int pc, int partner, Branch branch) {
    if constexpr (kPerVertex) {
      if (branch == Branch::kPerVertex) {
        host_.BeginIf(instruction);
        open_ifs_.push_back(partner);
        return pc + 1;
      }
    }
    (void)instruction;
    return branch == Branch::kAlways ? pc + 1 : Skip(partner);
  }

  int BreakIf(const Instruction& instruction, int pc, Branch branch) {
    if (branch == Branch::kNever) return pc + 1;
    if constexpr (kPerVertex) {
      if (!loops_.empty() && !host_.BreakLanes(instruction, branch)) return pc + 1;  // some vertices go on
    }
    (void)instruction;
    return Break(pc);
  }

  int EnterLoop(const Instruction& instruction, int pc, int partner) {
    const bool is_loop = instruction.opcode == Opcode::kLoop;
    const Vec4i counter = host_.Integer(instruction.sources[is_loop ? 1 : 0].reg.index);
    const int count = std::clamp(counter[0], 0, kMaxLoopCount);
    if (count == 0 || partner == kNoMatch) return Skip(partner);
    loops_.push_back({pc + 1, partner, count, counter[2], aL_, is_loop});
    if (is_loop) aL_ = counter[1];
    if constexpr (kPerVertex) host_.LoopEntered();
    return pc + 1;
  }

  int EndOfBody(int pc) {
    if (loops_.empty() || loops_.back().end != pc) return pc + 1;  // only an unvalidated program
    LoopFrame& frame = loops_.back();
    if (frame.is_loop) aL_ += frame.step;
    if (--frame.remaining > 0) {
      if constexpr (kPerVertex) host_.NextIteration();
      return frame.first;
    }
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
    if constexpr (kPerVertex) host_.LoopLeft();
  }

  const Program& program_;
  const ControlTable& control_;
  Host& host_;
  int& aL_;
  const int call_depth_;
  std::vector<LoopFrame> loops_;
  std::vector<CallFrame> calls_;
  std::vector<int> open_ifs_;  // per-vertex ifs: where each one's else or endif is
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
// an instruction whose comparison is none of the six (texldl is EngineRefusal's: batch and jit run it,
// gl does not). Every arithmetic row, _sat, _abs, a0's four lanes, r0-r31 and dynamic flow run.
Status StaticFlowRefusal(const Program& program, std::string_view engine);

// `program` (which passes StaticFlowRefusal) as a straight-line program for the constants `key` (its
// version semantics::kLaterModelStraightLine: read as vs_1_1, with r0-r31 and a0's lanes), or why not
// (the walk exceeds kMaxStaticFlowSteps or the result kMaxUnrolledInstructions; an unvalidated ret or
// break under a per-vertex condition). Dynamic flow becomes execution masks: setp, min, slt and sge
// on predicate registers p1, p2, ... (1 or 0 per vertex) and instructions predicated by them, which
// the engines run as arithmetic plus setp and predicated writes (vm/core/operands.h). Its constants are
// the later model's bank: run it with ModelConstants(program, api_constants). It has no dcl or def.
Result<Program> SpecialiseStaticFlow(const Program& program, const StaticFlowKey& key, std::string_view engine);

// The bank a later model's program sees: at least the model's constants (vs_2_0 on: 256, which the
// validator lets a program read whatever the API bank's size), its definitions written over the API's
// values.
ConstantBank ModelConstants(const Program& program, ConstantBank api_constants);

}  // namespace vs11
