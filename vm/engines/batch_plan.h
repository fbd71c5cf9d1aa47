// The batch engine's compiled form of a program: a flat list of steps, each one call of a SIMD kernel
// over every vertex of a batch. Built once per program (BuildBatchPlan); the kernels themselves are
// compiled once per Highway target (vm/engines/batch_kernels-inl.h) and reached through a KernelTable.
//
// Data layout while a batch runs: every register component the program touches is a "lane", an array
// of one float per vertex of the batch (structure of arrays). Steps name lanes by their index in the
// lane table; the engine points the input and output entries at the caller's arrays (or at padded
// copies for a short last batch) before each batch, and the other entries at its own scratch arena.
// Constants are not lanes: a step reads them as one float broadcast to every vertex.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "vm/core/isa.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11::batch {

// Vertices per batch: the lanes a typical program touches (about 20) then fit in a 32 KiB L1 cache.
inline constexpr std::size_t kBatchSize = 256;
// Kernels run over a whole number of these vertices (a multiple of every target's vector length, up
// to 2048-bit vectors); a short last batch is padded up to it.
inline constexpr std::size_t kVertexGranule = 64;
static_assert(kBatchSize % kVertexGranule == 0);

// ---- lane table ----------------------------------------------------------------------------------
inline constexpr std::uint16_t kNoLane = 0xFFFF;
inline constexpr int kInputLaneBase = 0;  // v#.c at kInputLaneBase + 4 # + c
inline constexpr int kOutputLaneBase = kInputLaneBase + 4 * kInputRegisterCount;  // output slot s, lane c
inline constexpr int kArenaLaneBase = kOutputLaneBase + 4 * kOutputSlotCount;     // engine-owned lanes
// The first two arena lanes hold constant vectors, for operands that must be arrays (see UnifyKind in batch_plan.cc).
inline constexpr int kZeroLane = kArenaLaneBase;    // all 0.0f
inline constexpr int kOneLane = kArenaLaneBase + 1;  // all 1.0f (w of an absent input, §1.2)
inline constexpr int kFixedArenaLanes = 2;

constexpr int InputLane(int reg, int component) { return kInputLaneBase + 4 * reg + component; }
constexpr int OutputLane(int slot, int component) { return kOutputLaneBase + 4 * slot + component; }

// ---- constant table ------------------------------------------------------------------------------
// Flat floats: row 0 is (0, 0, 0, 0), read by every operand that is statically zero (an unwritten
// temporary, a register past the end of its file) and by out-of-range relative reads; register c#
// follows at row kFirstConstantRow + #.
inline constexpr int kFirstConstantRow = 1;
inline constexpr std::uint32_t kZeroConstant = 0;
constexpr std::uint32_t ConstantIndex(int reg, int component) {
  return static_cast<std::uint32_t>(4 * (kFirstConstantRow + reg) + component);
}

// One component of a source as a step reads it: a lane (`is_array`) or a broadcast constant.
struct Operand {
  std::uint32_t index = kZeroConstant;  // lane table index, or constant table index
  bool is_array = false;
  friend constexpr bool operator==(const Operand&, const Operand&) = default;
};

// How a kernel loads a whole source; chosen per step so the vertex loop has no branches.
enum class OperandKind : std::uint8_t { kArray, kNegatedArray, kBroadcast };
inline constexpr int kOperandKinds = 3;

// A sampler as texldl's kernel reads it: the texture's shape and its texels (VertexTexture::texels,
// channels interleaved); texels null where the sampler is unbound.
struct TextureView {
  TextureShape shape;
  const float* texels = nullptr;
};

// What a kernel sees of the batch being run.
struct Frame {
  const float* const* read_lanes;  // lane table, for loads
  float* const* write_lanes;       // lane table, for stores (inputs: nullptr)
  const float* constants;          // constant table (rows as above)
  std::int32_t* address;           // a0 of each vertex: lane l (x, y, z, w) at address + l * kBatchSize
  std::int32_t constant_count;     // registers in the bank: relative reads outside [0, count) read 0
  std::size_t count;               // vertices to compute, a multiple of kVertexGranule
  const TextureView* textures = nullptr;  // s0..s3 (texldl)
};

struct Step;
using Kernel = void (*)(const Step& step, const Frame& frame);

// One kernel call. The meaning of the operand arrays depends on the kernel family:
//   lane (componentwise): sources[s][l] is source s's component for written lane l, to dest[l];
//   scalar: sources[0][0] is the swizzled w component, result to dest[0];
//   dot: sources[0][0..width) is the vector, sources[1 + r] row r, result of row r to dest[r];
//   vector (lit, dst, expp, logp): sources[s][c] component c of source s, result c to dest[c];
//   copy: sources[0][0] to dest[0]; address: sources[0][0] to a0.<address_lane> (Frame::address);
//   gather: component c of c[a0.<address_lane> + base] to dest[c];
//   texture (texldl): sampler s<base> at (u, v) = (sources[0][0], sources[0][1]), the sample's
//   component sources[1][c].index (s#'s swizzle) to dest[c].
// negate[i] applies to broadcast operands of sources[i] (array kinds carry it in OperandKind).
struct Step {
  Kernel kernel = nullptr;
  std::array<std::array<Operand, 4>, 5> sources{};
  std::array<bool, 5> negate{};
  std::array<std::uint16_t, 4> dest = {kNoLane, kNoLane, kNoLane, kNoLane};
  std::int32_t base = 0;
  std::uint8_t address_lane = 0;  // gather and address steps: the lane of a0 (0 for vs_1_1's a0.x)
};

// The sources a componentwise kernel reads: sgn's second and third (vs_2_0's scratch registers, which
// its semantics leave alone) are neither loaded nor given kernels for their kinds.
constexpr int KernelArity(const OpcodeInfo& info) { return info.opcode == Opcode::kSgn ? 1 : info.source_count(); }

// The kernels of one Highway target, indexed by opcode and operand kinds.
struct KernelTable {
  // Componentwise ops: [opcode][lanes - 1][k0 + 3 k1 + 9 k2] over the opcode's sources.
  std::array<std::array<std::array<Kernel, 27>, 4>, kOpcodeCount> lane{};
  // Scalar ops (rcp, rsq, exp, log): [opcode][kind].
  std::array<std::array<Kernel, kOperandKinds>, kOpcodeCount> scalar{};
  // lit, dst, expp, logp: operands of any kind, looked at per component.
  std::array<Kernel, kOpcodeCount> vector{};
  // Dot products and matrix rows: [width - 3][rows - 1][vector kind + 3 row kind].
  std::array<std::array<std::array<Kernel, 9>, 4>, 2> dot{};
  Kernel gather = nullptr;
  Kernel texture = nullptr;  // texldl (vm/core/texture_sampling.h)
  // setp (semantics::Compare, 1 where it holds, else 0): [comparison - 1][lanes - 1][k0 + 3 k1].
  std::array<std::array<std::array<Kernel, 27>, 4>, 6> compare{};
  // A predicated write (semantics::PredicatedWrite), sources (predicate, new value, old value):
  // [!p][lanes - 1][k0 + 3 k1 + 9 k2]. A predicated instruction computes into scratch lanes first.
  std::array<std::array<std::array<Kernel, 27>, 4>, 2> predicated{};
  // _sat on a destination, in place: [lanes - 1], dest[l] = saturate(sources[0][l]) over array lanes.
  std::array<Kernel, 4> saturate{};
};

// Target-independent kernels (memory moves and the a0 conversion, shared with the reference engine).
void CopyKernel(const Step& step, const Frame& frame);
void AddressKernel(const Step& step, const Frame& frame);

struct BatchPlan {
  std::vector<Step> steps;
  int arena_lanes = kFixedArenaLanes;        // lanes at kArenaLaneBase.. the engine must provide
  std::vector<std::uint16_t> input_lanes;    // input lanes the steps read
  std::vector<std::uint16_t> output_lanes;   // output lanes the steps write
  std::array<std::uint8_t, kOutputSlotCount> stored_lanes{};  // per slot, bit c: lane c is stored
  int max_static_constant = -1;  // highest constant register read at a fixed index
};

// Decodes `program` (well formed, as Decode accepts) into steps whose kernels come from `kernels`.
BatchPlan BuildBatchPlan(const Program& program, const KernelTable& kernels);

}  // namespace vs11::batch
