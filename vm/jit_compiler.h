// The jit engine's compiler: a whole vs_1_1 program becomes one x86-64 AVX2 loop (xbyak) that runs
// it on 8 vertices per iteration with the values in registers. The batch engine's kernels store every
// instruction's result to memory and load it back in the next step; this loop does not, which is
// what the batch engine loses to hand-written SIMD code.
//
// Bit exactness: the program is traced through the very templates of vm/semantics.h with a lane type
// that records operations instead of computing them, so the machine code performs the reference
// engine's IEEE operations in the reference engine's order (unfused, floor/sqrt/div exact).
//
// The compiled loop reads and writes the batch engine's lane table and constant table
// (vm/batch_plan.h), so it slots into the batch engine in place of its kernel steps.
#pragma once

#include <cstddef>
#include <memory>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vm/program.h"

namespace vs11::jit {

class CompiledProgram {
 public:
  virtual ~CompiledProgram() = default;
  // Runs the program on `count` vertices (a multiple of 8) of the lanes in the tables; `spill` has
  // spill_floats() floats of scratch (one buffer per thread).
  virtual void Run(const float* const* read_lanes, float* const* write_lanes, const float* constants,
                   std::size_t count, float* spill) const = 0;
  virtual std::size_t spill_floats() const = 0;
  // The machine code, and how many values the register allocator had to spill (for tests and notes).
  virtual std::span<const std::uint8_t> code() const = 0;
  virtual int spilled_values() const = 0;
};

// Compiles `program` (well formed, as Decode accepts). nullptr, with `why_not` set, when the CPU has
// no AVX2 or the program writes a0 (relative addressing stays with the batch kernels).
std::unique_ptr<CompiledProgram> Compile(const Program& program, std::string& why_not);

}  // namespace vs11::jit
