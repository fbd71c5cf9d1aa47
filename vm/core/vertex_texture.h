// Vertex textures (vs_3_0's texldl): a 2D texture bound to one of the four vertex samplers s0..s3, and
// the sampler state that decides how a coordinate outside [0, 1) reads. What is modelled is what D3D9
// drivers offer for vertex textures: the formats R32F and A32B32G32R32F, one level, point sampling;
// address modes wrap (the default), clamp and border (border colour 0 only). The sampling arithmetic
// is vm/core/texture_sampling.h. Source: Microsoft's D3D9 documentation (texldl - vs,
// D3DSAMPLERSTATETYPE), as the README's machine section gives it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "vm/core/result.h"

namespace vs11 {

// D3DVERTEXTEXTURESAMPLER0..3.
inline constexpr int kVertexSamplerCount = 4;

// The formats D3D9 allows for vertex textures that vs11 models.
enum class TextureFormat : std::uint8_t {
  kR32F,           // one float per texel; samples as (r, 1, 1, 1)
  kA32B32G32R32F,  // four floats per texel (r, g, b, a); samples as they are
};
inline constexpr int ChannelCount(TextureFormat format) { return format == TextureFormat::kR32F ? 1 : 4; }

// D3DTEXTUREADDRESS, the modes modelled: wrap (u - floor(u)), clamp (to the edge texels) and border
// (outside [0, 1) reads the border colour, which is 0: D3DSAMP_BORDERCOLOR's default).
enum class TextureAddress : std::uint8_t { kWrap, kClamp, kBorder };

// D3DSAMPLERSTATETYPE as vertex texturing uses it. The filters stay at their defaults (MAGFILTER and
// MINFILTER point, MIPFILTER none, MAXMIPLEVEL and MIPMAPLODBIAS 0): with one level, texldl's LOD
// (src0.w) picks level 0 whatever it is.
struct SamplerState {
  TextureAddress address_u = TextureAddress::kWrap;
  TextureAddress address_v = TextureAddress::kWrap;
  friend bool operator==(const SamplerState&, const SamplerState&) = default;
};

// The most texels a texture may have: a texel's number y * width + x is computed in float
// (vm/core/texture_sampling.h), exact below 2^24.
inline constexpr std::size_t kMaxTextureTexels = std::size_t{1} << 24;

// One level of a 2D texture: texel (x, y) is texels[(y * width + x) * ChannelCount(format) + channel],
// row y = 0 first (v = 0 is the top row, as in D3D).
struct VertexTexture {
  TextureFormat format = TextureFormat::kA32B32G32R32F;
  int width = 0;
  int height = 0;
  std::vector<float> texels;

  // The texture, or why not (kInvalidArgument): sizes from 1, at most kMaxTextureTexels texels, and
  // texels.size() == width * height * channels. Powers of two are not required.
  static Result<VertexTexture> Make(TextureFormat format, int width, int height, std::vector<float> texels);
};

// What a sampler holds: a texture (null: unbound, reads (0, 0, 0, 1)) and its state. Textures are
// shared, never written once bound, so a bank copies them cheaply.
struct SamplerBinding {
  std::shared_ptr<const VertexTexture> texture;
  SamplerState state;
};
using SamplerBank = std::array<SamplerBinding, kVertexSamplerCount>;

// What a specialised engine compiles in (vm/core/static_flow.h): each sampler's shape, not its texels.
struct TextureShape {
  bool bound = false;
  TextureFormat format = TextureFormat::kA32B32G32R32F;
  int width = 0;
  int height = 0;
  SamplerState state;
  friend bool operator==(const TextureShape&, const TextureShape&) = default;
};
TextureShape ShapeOf(const SamplerBinding& binding);

std::string TextureFormatName(TextureFormat format);  // "R32F", "A32B32G32R32F"

}  // namespace vs11
