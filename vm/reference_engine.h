// The scalar reference interpreter: one vertex at a time, float32, exactly the spec's pseudo-code
// (§3.1: all sources fetched before the masked store). The yardstick every other engine must equal.
#pragma once

#include <memory>

#include "vm/machine.h"

namespace vs11 {

// The complete register state of one vertex while a program runs.
struct VertexState {
  std::array<Vec4f, kInputRegisterCount> inputs;
  std::array<Vec4f, kTempRegisterCount> temps{};
  std::array<Vec4f, kOutputSlotCount> outputs{};
  int a0 = 0;
};

// a0.x = floor(x) (§1.5). NaN and values beyond +-2^20 become +-2^20, which puts every relative read
// out of range, so it reads 0 (the bank holds at most 2048 registers).
inline constexpr int kAddressLimit = 1 << 20;
int AddressFromFloat(float x);

// Runs `program` (def constants already folded into `constants`) on one vertex.
void RunVertex(const Program& program, const ConstantBank& constants, VertexState& state);

std::unique_ptr<Engine> MakeReferenceEngine(const Program& program, const ConstantBank& api_constants);

}  // namespace vs11
