#include "vm/capi/vertex_formats.h"

#include <array>
#include <bit>
#include <cmath>
#include <cassert>
#include <cstring>
#include <utility>

#include <glm/gtc/packing.hpp>
#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace vs11::capi {
namespace {

// D3DDECLTYPE's sizes in bytes, in DeclType order.
constexpr std::array<std::size_t, kDeclTypeCount> kSizes = {4, 8, 12, 16, 4, 4, 4, 8, 4, 4, 8, 4, 8, 4, 4, 4, 8};

// The buffers are little-endian, as D3D's are; so is every machine the engines run on.
static_assert(std::endian::native == std::endian::little);

template <class T>
T Load(const std::uint8_t* bytes, int index) {
  T value;
  std::memcpy(&value, bytes + index * sizeof(T), sizeof(T));
  return value;
}

// Components 0..count-1 from `read(i)`, the rest from kDefaultInput.
template <class Read>
Vec4f Fill(int count, Read read) {
  Vec4f value = kDefaultInput;
  for (int i = 0; i < count; ++i) value[i] = read(i);
  return value;
}

constexpr int kDecBits = 10;
constexpr std::uint32_t kDecMask = (1u << kDecBits) - 1;
constexpr float kUbyteNorm = 255.0f, kShortNorm = 32767.0f, kUshortNorm = 65535.0f, kDecNorm = 511.0f;

float DecComponent(std::uint32_t word, int i, bool is_signed) {
  const std::uint32_t bits = (word >> (kDecBits * i)) & kDecMask;
  if (!is_signed) return static_cast<float>(bits);
  const int value = static_cast<int>(bits) - ((bits & (1u << (kDecBits - 1))) ? (1 << kDecBits) : 0);
  return static_cast<float>(value) / kDecNorm;
}

}  // namespace

std::optional<std::size_t> DeclTypeSize(int type) {
  if (type < 0 || type >= kDeclTypeCount) return std::nullopt;
  return kSizes[static_cast<std::size_t>(type)];
}

float HalfToFloat(std::uint16_t half) { return glm::unpackHalf1x16(half); }

namespace {

// The reading of one element; always inlined, so that ReadElements's loops, each for one constant
// type, keep only that type's case.
[[gnu::always_inline]] inline Vec4f Read(DeclType type, const std::uint8_t* bytes) {
  switch (type) {
    case DeclType::kFloat1:
    case DeclType::kFloat2:
    case DeclType::kFloat3:
    case DeclType::kFloat4:
      return Fill(static_cast<int>(type) + 1, [&](int i) { return Load<float>(bytes, i); });
    case DeclType::kD3dColor:
      // Memory holds B, G, R, A; the shader sees R, G, B, A.
      return {bytes[2] / kUbyteNorm, bytes[1] / kUbyteNorm, bytes[0] / kUbyteNorm, bytes[3] / kUbyteNorm};
    case DeclType::kUbyte4:
      return Fill(4, [&](int i) { return static_cast<float>(bytes[i]); });
    case DeclType::kShort2:
    case DeclType::kShort4:
      return Fill(type == DeclType::kShort2 ? 2 : 4,
                  [&](int i) { return static_cast<float>(Load<std::int16_t>(bytes, i)); });
    case DeclType::kUbyte4n:
      return Fill(4, [&](int i) { return bytes[i] / kUbyteNorm; });
    case DeclType::kShort2n:
    case DeclType::kShort4n:
      return Fill(type == DeclType::kShort2n ? 2 : 4,
                  [&](int i) { return static_cast<float>(Load<std::int16_t>(bytes, i)) / kShortNorm; });
    case DeclType::kUshort2n:
    case DeclType::kUshort4n:
      return Fill(type == DeclType::kUshort2n ? 2 : 4,
                  [&](int i) { return static_cast<float>(Load<std::uint16_t>(bytes, i)) / kUshortNorm; });
    case DeclType::kUdec3:
    case DeclType::kDec3n: {
      const std::uint32_t word = Load<std::uint32_t>(bytes, 0);
      return Fill(3, [&](int i) { return DecComponent(word, i, type == DeclType::kDec3n); });
    }
    case DeclType::kFloat16x2:
    case DeclType::kFloat16x4:
      return Fill(type == DeclType::kFloat16x2 ? 2 : 4,
                  [&](int i) { return HalfToFloat(Load<std::uint16_t>(bytes, i)); });
    case DeclType::kUnused:
      break;
  }
  return kDefaultInput;
}

template <DeclType kType>
void ReadLoop(const std::uint8_t* bytes, std::size_t stride, std::size_t count, const std::array<float*, 4>& lanes) {
  for (std::size_t i = 0; i < count; ++i) {
    const Vec4f value = Read(kType, bytes + i * stride);
    for (int c = 0; c < 4; ++c) lanes[c][i] = value[c];
  }
}

template <int... kTypes>
constexpr auto MakeReadLoops(std::integer_sequence<int, kTypes...>) {
  return std::array{&ReadLoop<static_cast<DeclType>(kTypes)>...};
}
constexpr auto kReadLoops = MakeReadLoops(std::make_integer_sequence<int, kDeclTypeCount>());

}  // namespace

Vec4f ReadElement(DeclType type, const std::uint8_t* bytes) { return Read(type, bytes); }

void ReadElements(DeclType type, const std::uint8_t* bytes, std::size_t stride, std::size_t count,
                  const std::array<float*, 4>& lanes) {
  if (type == DeclType::kUnused) return;
  kReadLoops[static_cast<std::size_t>(type)](bytes, stride, count, lanes);
}

namespace {

// value * 255 rounded to nearest, ties to even: the SSE conversion (in the default rounding mode)
// where there is one, as std::nearbyint's libm call costs more than the rest of the packing.
[[gnu::always_inline]] inline std::uint32_t ColorChannel(float value) {
  if (!(value > 0.0f)) return 0;  // NaN too
  if (value >= 1.0f) return 255;
#if defined(__SSE__)
  return static_cast<std::uint32_t>(_mm_cvtss_si32(_mm_set_ss(value * kUbyteNorm)));
#else
  return static_cast<std::uint32_t>(std::nearbyint(value * kUbyteNorm));
#endif
}

[[gnu::always_inline]] inline std::uint32_t Pack(float r, float g, float b, float a) {
  constexpr int kRed = 16, kGreen = 8, kAlpha = 24;
  return ColorChannel(a) << kAlpha | ColorChannel(r) << kRed | ColorChannel(g) << kGreen | ColorChannel(b);
}

template <DeclType kType>
void WriteLoop(const std::array<StridedLane, 4>& lanes, std::uint8_t* bytes, std::size_t stride, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    std::uint8_t* at = bytes + i * stride;
    if constexpr (kType == DeclType::kD3dColor) {
      const std::uint32_t color = Pack(lanes[0][i], lanes[1][i], lanes[2][i], lanes[3][i]);
      std::memcpy(at, &color, sizeof color);
    } else {
      constexpr int kCount = static_cast<int>(kType) + 1;
      float values[kCount];
      for (int c = 0; c < kCount; ++c) values[c] = lanes[c][i];
      std::memcpy(at, values, sizeof values);
    }
  }
}

}  // namespace

std::uint32_t PackD3dColor(const Vec4f& rgba) { return Pack(rgba[0], rgba[1], rgba[2], rgba[3]); }

bool IsWritableType(DeclType type) { return type <= DeclType::kD3dColor; }

void WriteElements(DeclType type, const std::array<StridedLane, 4>& lanes, std::uint8_t* bytes, std::size_t stride,
                   std::size_t count) {
  switch (type) {
    case DeclType::kFloat1: return WriteLoop<DeclType::kFloat1>(lanes, bytes, stride, count);
    case DeclType::kFloat2: return WriteLoop<DeclType::kFloat2>(lanes, bytes, stride, count);
    case DeclType::kFloat3: return WriteLoop<DeclType::kFloat3>(lanes, bytes, stride, count);
    case DeclType::kFloat4: return WriteLoop<DeclType::kFloat4>(lanes, bytes, stride, count);
    case DeclType::kD3dColor: return WriteLoop<DeclType::kD3dColor>(lanes, bytes, stride, count);
    default: assert(!"not an output type");
  }
}

void WriteElement(DeclType type, const Vec4f& value, std::uint8_t* bytes) {
  WriteElements(type, {StridedLane{&value[0], 0}, StridedLane{&value[1], 0}, StridedLane{&value[2], 0}, StridedLane{&value[3], 0}},
                bytes, 0, 1);
}

}  // namespace vs11::capi
