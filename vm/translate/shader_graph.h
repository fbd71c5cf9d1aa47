// A vs_1_1 program as the translator sees it: vm/core/semantics.h traced with a lane type that records
// each operation as a node (as the jit's tracer does, vm/engines/jit_graph.h), so the emitted code
// performs the engines' IEEE operations in the engines' order. vs_1_1 has no branches, so the trace is
// straight-line code over scalars: one node per float, int or bool operation, shared when identical
// (v0.x read by three dp4s is one node).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11::translate {

enum class ValueType : std::uint8_t { kFloat, kInt, kBool, kVec4 };

enum class NodeOp : std::uint8_t {
  kFloatLiteral,  // immediate: the float's bits
  kIntLiteral,    // immediate: the int32's bits
  kInput,         // immediate: register * 4 + lane (v#.lane)
  kConstant,      // immediate: register * 4 + lane (c#.lane, not overridden by a def)
  kRelativeRow,   // args: register number (int); the vec4 c[i] as the engines read it (def, range)
  kComponent,     // args: a vec4; immediate: lane
  kAdd, kSub, kMul, kDiv,
  kFloor, kSqrt, kAbs, kNegate, kIsNaN,
  kLess, kGreater, kGreaterEqual, kEqual,  // floats to bool
  kSelect,        // args: bool, yes, no
  kBitsOf, kFloatFromBits, kToInt, kToFloat,
  kIntAdd, kIntSub, kIntAnd, kIntOr, kIntGreater,
  kShiftLeft, kShiftRight,  // immediate: the shift count; right is arithmetic
};

inline constexpr int kNoNode = -1;

struct Node {
  NodeOp op;
  ValueType type;
  std::array<int, 3> args = {kNoNode, kNoNode, kNoNode};
  std::uint32_t immediate = 0;
  int instruction = -1;  // the instruction whose trace created it (-1: before the first)
};

struct ShaderGraph {
  std::vector<Node> nodes;
  // The final value of every lane of every output slot (OutputSlot order), written or not: unwritten
  // lanes hold the engines' values (UnwrittenOutputValue, 0 for the unwritten lanes of a written slot).
  std::array<std::array<int, 4>, kOutputSlotCount> outputs{};
  std::array<WriteMask, kOutputSlotCount> written{};
  // The def constants inside the bank (a def wins over the bank, ApplyDefinitions), by register.
  std::map<int, std::array<std::uint32_t, 4>> definitions;
  int constant_count = kDefaultConstantCount;
  std::vector<bool> inputs_read = std::vector<bool>(kInputRegisterCount, false);
};

// Traces `program` against a bank of `constant_count` registers: static reads past it read 0, as
// ConstantBank::Read does. Products follow `rules` as semantics::Product writes them (under kLegacy,
// compares and selects around each multiply).
ShaderGraph TraceShader(const Program& program, int constant_count, FloatRules rules = FloatRules::kD3d9);

// Which nodes the outputs depend on.
std::vector<bool> LiveNodes(const ShaderGraph& graph);

}  // namespace vs11::translate
