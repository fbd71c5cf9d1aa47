// texldl's point sampling, written once over a lane type V (float for the reference engine, a
// Highway vector for batch, a recorded value for the IR), as vm/core/semantics.h's kernels are.
//
// The rule (Microsoft's texldl and D3DSAMPLERSTATETYPE pages; the README's machine section): on an
// axis of N texels, coordinate u reads texel floor(u' * N), u' being u after the address mode (wrap:
// u - floor(u); clamp and border: u itself), the index then clamped to [0, N - 1]. Texel centres sit
// at (i + 0.5) / N, so u * N an exact integer k reads texel k: the edge belongs to the texel on its
// right (floor), our choice where the reference leaves the rounding open. Border reads 0 in every
// channel where u is outside [0, 1). A NaN coordinate reads texel 0 (border: 0); wrap maps +-inf to
// NaN. R32F samples as (r, 1, 1, 1), an unbound sampler as (0, 0, 0, 1). With one level and the
// default filters (MIPFILTER none, MAXMIPLEVEL 0), src0.w, the LOD, picks level 0 whatever its value,
// so it is not read.
#pragma once

#include <cstdint>

#include "vm/core/program.h"
#include "vm/core/semantics.h"
#include "vm/core/vertex_texture.h"

namespace vs11::semantics {

// The texel index, as a float in [0, size - 1], that u reads on an axis of `size` texels.
template <class V>
V TexelOnAxis(V u, int size, TextureAddress mode) {
  const V zero = Constant(u, 0.0f);
  const V last = Constant(u, static_cast<float>(size - 1));
  // Wrap: a tiny negative u gives 1 - u rounded to 1.0, which lands past the last texel and is
  // clamped back to it, where the wrap puts it.
  const V mapped = mode == TextureAddress::kWrap ? u - Floor(u) : u;
  const V index = Floor(mapped * Constant(u, static_cast<float>(size)));
  const V above_zero = IfThenElse(index > zero, index, zero);  // NaN fails the test: texel 0
  return IfThenElse(above_zero < last, above_zero, last);
}

// `value` where u lies in [0, 1), else the border colour's 0 (NaN included), under border addressing.
template <class V>
V InsideBorder(V u, V value, TextureAddress mode) {
  if (mode != TextureAddress::kBorder) return value;
  const V zero = Constant(u, 0.0f);
  return IfThenElse(u >= zero, IfThenElse(u < Constant(u, 1.0f), value, zero), zero);
}

// A texture reader R gives what a lane type's engine knows of the samplers:
//   TextureShape Shape(int sampler) const;            // unbound where the sampler has no texture
//   Vec4<V> Texel(int sampler, I index) const;        // texel number `index` (y * width + x) as stored:
//                                                     // R32F's r in x, the other lanes any value
// The sample of sampler `sampler` at (u, v) = coordinate's x and y.
template <class R, class V>
Vec4<V> SampleTexture(const R& reader, int sampler, const Vec4<V>& coordinate) {
  const TextureShape shape = reader.Shape(sampler);
  const V zero = Constant(coordinate[0], 0.0f), one = Constant(coordinate[0], 1.0f);
  if (!shape.bound) return {zero, zero, zero, one};
  const V x = TexelOnAxis(coordinate[0], shape.width, shape.state.address_u);
  const V y = TexelOnAxis(coordinate[1], shape.height, shape.state.address_v);
  // y * width + x is exact: a texture has at most 2^24 texels (kMaxTextureTexels).
  const Vec4<V> texel = reader.Texel(sampler, ToInt(y * Constant(x, static_cast<float>(shape.width)) + x));
  Vec4<V> value = shape.format == TextureFormat::kR32F ? Vec4<V>{texel[0], one, one, one} : texel;
  for (V& lane : value) {
    lane = InsideBorder(coordinate[0], lane, shape.state.address_u);
    lane = InsideBorder(coordinate[1], lane, shape.state.address_v);
  }
  return value;
}

// texldl dst, src0, s#: the sample at src0 (already fetched: swizzled, negated), then s#'s swizzle; the
// caller applies _sat and the write mask.
template <class R, class V>
Vec4<V> Texldl(const R& reader, const Instruction& instruction, const Vec4<V>& coordinate) {
  const SourceOperand& sampler = instruction.sources[1];
  const Vec4<V> sample = SampleTexture(reader, sampler.reg.index, coordinate);
  Vec4<V> result;
  for (int lane = 0; lane < 4; ++lane) result[lane] = sample[sampler.swizzle[lane]];
  return result;
}

}  // namespace vs11::semantics
