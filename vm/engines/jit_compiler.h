// The jit engine's compiler: a whole vs_1_1 program becomes one x86-64 loop (xbyak) that runs it on
// a vector of vertices per iteration (16 in zmm registers with AVX-512, 8 in ymm with AVX2; several
// vectors interleaved for long dependency chains) with the values in registers.
// The batch engine's kernels store every instruction's result to memory and load it back in the
// next step; this loop does not, which is what the batch engine loses to hand-written SIMD code.
//
// Bit exactness: the program is recorded into the IR (vm/ir/) through the very templates of
// vm/core/semantics.h, with a lane type that records operations instead of computing them, so the
// machine code performs the reference engine's IEEE operations in the reference engine's order
// (unfused, floor/sqrt/div exact).
//
// The compiled loop reads and writes the batch engine's lane table and constant table
// (vm/engines/batch_plan.h), so it slots into the batch engine in place of its kernel steps.
#pragma once

#include <bit>
#include <cstddef>
#include <memory>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/engines/jit_options.h"

namespace vs11::jit {

// What one call of the compiled loop works on (the field order is part of the generated code).
struct RunArguments {
  const float* const* read_lanes;  // the lane table, for loads
  float* const* write_lanes;       // the lane table, for stores
  const float* constants;          // the constant table (rows as vm/engines/batch_plan.h lays them out)
  std::size_t count;               // vertices, any number (0 included): see CompiledProgram::Run
  const float* literals;           // filled in by CompiledProgram::Run
  float* spill;                    // spill_floats() floats of scratch, one buffer per thread
  std::int32_t constant_count;     // registers in the bank: relative reads outside [0, count) read 0
};

// A call whose outputs (vertices x stored lanes x 4 bytes) reach this size, with every output lane
// aligned to a vector, stores them around the caches (vmovntps): they would not stay there, and a
// cached store first reads the line it overwrites.
// Only a loop that writes whole cache lines of each output lane per iteration streams (AVX-512, or two
// AVX2 vertex groups, whose stores of a lane are adjacent: vm/engines/jit_graph.cc): a streaming
// store of half a line leaves a partial line to the write-combining buffers, which write it out
// slowly. bench/README.md ("The jit's streaming stores") has the measurements.
inline constexpr std::size_t kStreamingOutputBytes = std::size_t{1} << 20;
inline constexpr std::size_t kCacheLineBytes = 64;

class CompiledProgram {
 public:
  virtual ~CompiledProgram() = default;
  // Computes vertices [0, count) of every lane and reads and writes nothing past them. The loop runs
  // whole iterations of vertices_per_iteration() in the caller's arrays; the rest (count modulo it)
  // runs once more on padded copies, slower: callers that want speed pass a multiple of
  // vertices_per_iteration() (every multiple of batch::kVertexGranule, vm/engines/batch_plan.h, is one).
  // Only the input and output entries of the lane table are read (batch::kInputLaneBase up to
  // batch::kArenaLaneBase), and only those the program uses.
  // Several threads may call Run at once (the batch engine's thread split does), each with its own
  // spill buffer and lane tables and with output ranges that do not overlap: the code and its
  // literals are only read.
  virtual void Run(RunArguments arguments) const = 0;
  virtual std::size_t spill_floats() const = 0;
  // The machine code, and how many values the register allocator had to spill (for tests and notes).
  virtual std::span<const std::uint8_t> code() const = 0;
  virtual int spilled_values() const = 0;
  virtual int spilled_masks() const = 0;  // of those, AVX-512 mask registers
  virtual JitIsa isa() const = 0;                // kAvx2 or kAvx512
  virtual int vertices_per_iteration() const = 0;  // lanes x interleaved vertex groups: 8, 16 or 32
};

// The instruction sets this CPU (and its operating system) runs, from narrowest to widest.
std::vector<JitIsa> SupportedIsas();

// An input lane that holds one value in every vertex (VertexArrays::uniform): compiled in, not read.
struct UniformInput {
  int reg;
  int component;
  float value;
  friend bool operator==(const UniformInput& a, const UniformInput& b) {  // NaNs by their bits
    return a.reg == b.reg && a.component == b.component &&
           std::bit_cast<std::uint32_t>(a.value) == std::bit_cast<std::uint32_t>(b.value);
  }
};

// Compiles `program` (well formed, as Decode accepts) for `isa` (kBest: the last of SupportedIsas),
// its products under `rules` (recorded in: the code of one rule holds no test for the other).
// The code never reads the `uniform_inputs` lanes.
// nullptr, with `why_not` set, when the CPU lacks that instruction set (or has no AVX2 at all), the
// program has texldl (vertex textures: the IR has no texture read yet), or, should it ever happen,
// code generation fails.
std::unique_ptr<CompiledProgram> Compile(const Program& program, std::string& why_not, JitIsa isa = JitIsa::kBest,
                                         std::span<const UniformInput> uniform_inputs = {},
                                         FloatRules rules = FloatRules::kD3d9);

}  // namespace vs11::jit
