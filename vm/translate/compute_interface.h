// The compute form of a translation (TranslateOptions::stage = Stage::kCompute, `vs11 translate
// --stage compute`): one invocation per vertex over storage buffers, for contexts without transform
// feedback (GLSL ES 3.10 and later, Vulkan). What an application binds, and the C++ image of the
// layout block it fills:
//
//   binding 0  uniform block Vs11Constants (std140): vec4 c[N], the constant bank (16-byte rows, D3D's
//              layout). A buffer that already lives on the GPU can be bound here as it is.
//   binding 1  uniform block Vs11Layout (std140): ComputeLayoutBlock below.
//   binding 2  storage buffer Vs11Inputs: float vs11_in[], the vertex inputs in any layout.
//   binding 3  storage buffer Vs11Outputs: float vs11_out[], where the outputs go.
//
// (GLSL ES numbers uniform blocks and storage buffers apart; Vulkan's set 0 holds all four, so the
// numbers differ.) Input register N, component c, of vertex i is vs11_in[input_base[N][c] + i *
// input_stride[N][0]]: structure of arrays (a lane per component, stride 1) and interleaved vertices
// (base = the element's offset within a vertex plus c, stride = the vertex's size) alike, in floats.
// A register whose input_stride[N][1] is 0 is not supplied and reads (0, 0, 0, 1). Outputs likewise
// (output_base, output_stride by OutputSlot); the shader writes the four lanes of every output
// register the program writes, where output_stride[slot][1] is 1, and nothing else: the rest of the
// output buffer is left as it was.
//
// The work groups are kComputeWorkGroupSize invocations along x; vertex i is the invocation
// gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * kComputeWorkGroupSize) + gl_GlobalInvocationID.x,
// and invocations at or past vertex_count do nothing, so a count beyond one dimension's limit of
// work groups (65535 in GLES 3.1) is dispatched in two dimensions (ComputeDispatchSize).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "vm/core/machine.h"

namespace vs11::translate {

inline constexpr int kComputeWorkGroupSize = 64;
inline constexpr int kComputeConstantsBinding = 0;
inline constexpr int kComputeLayoutBinding = 1;
inline constexpr int kComputeInputsBinding = 2;
inline constexpr int kComputeOutputsBinding = 3;

// The std140 image of the uniform block Vs11Layout: every uvec4 array element is 16 bytes.
struct ComputeLayoutBlock {
  using UVec4 = std::array<std::uint32_t, 4>;
  std::array<UVec4, kInputRegisterCount> input_base{};    // floats from vs11_in's start to vN.xyzw of vertex 0
  std::array<UVec4, kInputRegisterCount> input_stride{};  // [0]: floats from one vertex to the next; [1]: supplied
  std::array<UVec4, kOutputSlotCount> output_base{};
  std::array<UVec4, kOutputSlotCount> output_stride{};    // [0]: stride; [1]: 1 where the output is wanted
  std::uint32_t vertex_count = 0;
  std::uint32_t opaque_zero = 0;  // must be 0: the literals of an exact_on_driver translation read it
  std::uint32_t padding[2] = {};

  // Register `reg` supplied (or output `slot` wanted): component c of vertex i at base[c] + i * stride.
  // Structure of arrays: each lane's start and stride 1; interleaved: SetInterleavedInput.
  void SetInput(int reg, const UVec4& base, std::uint32_t stride);
  void SetInterleavedInput(int reg, std::uint32_t offset, std::uint32_t stride) {
    SetInput(reg, {offset, offset + 1, offset + 2, offset + 3}, stride);
  }
  void SetOutput(int slot, const UVec4& base, std::uint32_t stride);
};
static_assert(sizeof(ComputeLayoutBlock) == 16 * (2 * kInputRegisterCount + 2 * kOutputSlotCount + 1));

// Work groups along x and y for `vertex_count` vertices with at most `max_groups_x` groups along x
// (GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]; 65535 at least): x * y * kComputeWorkGroupSize >= count.
std::array<std::uint32_t, 2> ComputeDispatchSize(std::size_t vertex_count, std::uint32_t max_groups_x);

}  // namespace vs11::translate
