// Static flow control resolved for one set of integer and boolean constants, as drivers do: a later
// model's program (vs_2_0 on) whose rep/loop counts and if/call conditions come from i# and b# only
// becomes straight-line vs_1_1 code that the batch and jit engines run (vm/engines/static_flow_engine.h).
// The walk follows the reference engine's control rules (vm/engines/reference_flow.cc) exactly: loop
// counts clamped to [0, 255], the outer aL restored when a loop ends, calls beyond the model's depth
// skipped, each c#[aL + n] read as the static c#[k] of its iteration.
#pragma once

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

// What a specialisation depends on: the integer and boolean constants after defi/defb.
struct StaticFlowKey {
  std::array<Vec4i, kIntegerConstantCount> integers{};
  std::array<bool, kBooleanConstantCount> booleans{};
  int constant_count = 0;  // the bank's size: a static c# past it reads 0
  friend bool operator==(const StaticFlowKey&, const StaticFlowKey&) = default;
  friend auto operator<=>(const StaticFlowKey&, const StaticFlowKey&) = default;
};
StaticFlowKey StaticFlowKeyOf(const ConstantBank& constants);  // constants: ModelConstants'

// Success, or why `engine` cannot run `program` (a later model) specialised, whatever the constants:
// dynamic flow control (if_comp, break_comp, breakp, setp, predicated instructions, if/callnz on p0),
// texldl, an instruction the engine has no kernel for (the later models' arithmetic rows: abs, crs,
// lrp, mova, nrm, pow, sgn, sincos), _sat and _abs, a0 lanes other than x, more than 12 temporaries.
Status StaticFlowRefusal(const Program& program, std::string_view engine);

// `program` (which passes StaticFlowRefusal) as a vs_1_1 program for the constants `key`, or why not
// (the walk exceeds kMaxStaticFlowSteps or the result kMaxUnrolledInstructions). Its constants are
// the later model's bank: run it with ModelConstants(program, api_constants). It has no dcl or def.
Result<Program> SpecialiseStaticFlow(const Program& program, const StaticFlowKey& key, std::string_view engine);

// The bank a later model's program sees: at least the model's constants (vs_2_0 on: 256, which the
// validator lets a program read whatever the API bank's size), its definitions written over the API's
// values.
ConstantBank ModelConstants(const Program& program, ConstantBank api_constants);

}  // namespace vs11
