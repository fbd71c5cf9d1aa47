// A vs_1_1 program as the translator sees it: the program recorded into the IR (vm/ir/record.h) with
// GLSL's registers as its bindings, so the emitted code performs the engines' IEEE operations in the
// engines' order. vs_1_1 has no branches, so the graph is straight-line code over scalars: one node
// per float, int or bool operation, shared when identical (v0.x read by three dp4s is one node).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/ir/graph.h"

namespace vs11::translate {

// Input nodes name v#.lane as register * 4 + lane, constant nodes c#.lane likewise (a register the
// program does not def); relative reads are kRelativeRow of the register number, then kComponent.
struct ShaderGraph {
  ir::Graph graph;
  // The final value of every lane of every output slot (OutputSlot order), written or not: unwritten
  // lanes hold the engines' values (UnwrittenOutputValue, 0 for the unwritten lanes of a written slot).
  std::array<std::array<int, 4>, kOutputSlotCount> outputs{};
  std::array<WriteMask, kOutputSlotCount> written{};
  // The def constants inside the bank (a def wins over the bank, ApplyDefinitions), by register.
  std::map<int, std::array<std::uint32_t, 4>> definitions;
  int constant_count = kDefaultConstantCount;
  std::vector<bool> inputs_read = std::vector<bool>(kInputRegisterCount, false);
};

// Records `program` against a bank of `constant_count` registers: static reads past it read 0, as
// ConstantBank::Read does. Products follow `rules` as semantics::Product writes them (under kLegacy,
// compares and selects around each multiply).
ShaderGraph RecordShader(const Program& program, int constant_count, FloatRules rules = FloatRules::kD3d9);

// Which nodes the outputs depend on.
std::vector<bool> LiveNodes(const ShaderGraph& shader);

}  // namespace vs11::translate
