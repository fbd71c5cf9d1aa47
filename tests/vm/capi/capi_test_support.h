// Token streams and vertex buffers for the C library's tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"

namespace vs11::capi::testing {

// The tokens Microsoft's assembler would write for `source` (which must assemble).
inline std::vector<std::uint32_t> Tokens(std::string_view source) {
  AssembleResult assembled = AssembleSource(source, "test.vsh", {});
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  return assembled.program ? Encode(*assembled.program) : std::vector<std::uint32_t>{};
}

// Appends a value's bytes to a vertex being built.
template <class T>
void Put(std::vector<std::uint8_t>& bytes, T value) {
  const std::size_t at = bytes.size();
  bytes.resize(at + sizeof value);
  std::memcpy(bytes.data() + at, &value, sizeof value);
}

// The skinning-like D3D9 program of the tests: four inputs over two streams, four outputs.
inline constexpr std::string_view kD3d9Program = R"(vs_1_1
dcl_position v0
dcl_color v1
dcl_texcoord0 v2
dcl_blendweight v3
m4x4 oPos, v0, c0
mov oD0, v1
mov oD1, v3
mov r0, c5
mad oT0, v2, c4, r0
)";

// Stream 0: float3 position, D3DCOLOR (16 bytes). Stream 1: FLOAT16_2 texcoord, DEC3N weight,
// SHORT4N padding nobody reads (16 bytes). Vertex i's values are simple functions of i.
struct TwoStreams {
  std::vector<std::uint8_t> stream0, stream1;
  static constexpr std::size_t kStride0 = 16, kStride1 = 16;
};
inline TwoStreams MakeTwoStreams(std::size_t count) {
  TwoStreams streams;
  for (std::size_t i = 0; i < count; ++i) {
    Put(streams.stream0, static_cast<float>(i));
    Put(streams.stream0, 0.5f);
    Put(streams.stream0, -2.0f);
    Put(streams.stream0, static_cast<std::uint32_t>(0x80FF2000u + (i & 0xFF)));  // A=0x80 R=0xFF G=0x20 B=i
    Put(streams.stream1, static_cast<std::uint16_t>(0x3C00));                     // 1.0
    Put(streams.stream1, static_cast<std::uint16_t>(0xB800));                     // -0.5
    Put(streams.stream1, static_cast<std::uint32_t>(0x1FFu | 0x200u << 10 | (i & 0x3FF) << 20));  // 511, -512, i
    Put(streams.stream1, static_cast<std::uint64_t>(0x7FFF7FFF7FFF7FFFull));
  }
  return streams;
}

}  // namespace vs11::capi::testing
