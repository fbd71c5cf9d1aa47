// The bytes of Direct3D 9 vertex buffers: every D3DDECLTYPE read into four floats (an input element),
// D3DCOLOR and floats written (an output element), and the half floats of FLOAT16_2/4. The values
// are d3d9types.h's; the readings are the D3D9 documentation's for D3DDECLTYPE ("expanded to").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "vm/core/machine.h"

namespace vs11::capi {

enum class DeclType : std::uint8_t {
  kFloat1 = 0, kFloat2, kFloat3, kFloat4,
  kD3dColor,   // 4 bytes B, G, R, A (a little-endian ARGB DWORD) -> (R, G, B, A) / 255
  kUbyte4,     // (x, y, z, w) as bytes
  kShort2, kShort4,
  kUbyte4n,    // / 255
  kShort2n, kShort4n,    // / 32767 (-32768 gives -1.0000305: D3D9 does not clamp)
  kUshort2n, kUshort4n,  // / 65535
  kUdec3,      // 10-10-10 unsigned, x in the low bits, the top two bits ignored
  kDec3n,      // 10-10-10 signed, / 511 (-512 gives -1.0019569)
  kFloat16x2, kFloat16x4,
  kUnused,     // D3DDECLTYPE_UNUSED: D3DDECL_END's type
};
inline constexpr int kDeclTypeCount = static_cast<int>(DeclType::kUnused);  // the readable ones

// D3DDECLUSAGE values the library maps (vm/core/isa.h has the dcl_ names of all of them).
enum class DeclUsage : std::uint8_t {
  kPosition = 0, kBlendWeight, kBlendIndices, kNormal, kPointSize, kTexCoord, kTangent, kBinormal,
  kTessFactor, kPositionT, kColor, kFog, kDepth, kSample,
};

// The bytes one element of `type` occupies; nullopt for a type that is not a D3DDECLTYPE.
std::optional<std::size_t> DeclTypeSize(int type);

// The four floats of an element of `type` (a readable type) whose bytes start at `bytes`, with the
// components the type lacks filled from kDefaultInput (0, 0, 0, 1).
Vec4f ReadElement(DeclType type, const std::uint8_t* bytes);
// ReadElement over `count` elements `stride` bytes apart, component c of element i into lanes[c][i].
void ReadElements(DeclType type, const std::uint8_t* bytes, std::size_t stride, std::size_t count,
                  const std::array<float*, 4>& lanes);

// IEEE half to float, exactly (every half is a float): denormals, infinities and NaN payloads kept.
float HalfToFloat(std::uint16_t half);

// A colour output as D3DCOLOR's DWORD (A in the top byte, B in the low one): each lane clamped to
// [0, 1], times 255, rounded to nearest (ties to even); NaN gives 0.
std::uint32_t PackD3dColor(const Vec4f& rgba);

// FLOAT1-4 and D3DCOLOR, the only output types of the library.
bool IsWritableType(DeclType type);
// Writes `value` at `bytes` as `type` (a writable one): its first 1-4 floats, or PackD3dColor.
void WriteElement(DeclType type, const Vec4f& value, std::uint8_t* bytes);
// WriteElement over `count` elements `stride` bytes apart, element i from lanes[c][i].
void WriteElements(DeclType type, const std::array<StridedLane, 4>& lanes, std::uint8_t* bytes, std::size_t stride,
                   std::size_t count);

}  // namespace vs11::capi
