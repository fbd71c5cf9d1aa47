// The projection's SIMD kernels, compiled once per Highway target (hwy/foreach_target.h) and
// dispatched at run time. See irradiance/sh/projection_kernels.h.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "irradiance/sh/projection_kernels.cc"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "hwy/highway.h"
#include "irradiance/sh/projection_kernels.h"

HWY_BEFORE_NAMESPACE();
namespace vs11::irradiance::kernels {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Terms each float lane sums before the block's sums go into double (a block is this many vectors
// of a row: 256 texels with AVX-512, 16 with the scalar target), the same precision on every target.
constexpr int kTermsPerLane = 16;
constexpr std::size_t kMaxFloatLanes = HWY_MAX_BYTES / sizeof(float);
constexpr int kSums = kMomentSums;
constexpr int kFaces = 6;

// Per-texel weights of one face row (see FaceWeights).
struct RowWeights {
  const float* q;
  const float* qr;
  const float* qr2;
};

using DF = hn::ScalableTag<float>;
using VF = hn::Vec<DF>;

// The sum of the float lanes of `v` pairwise in double: lane j plus lane j + half, on half as many
// double lanes.
#if HWY_TARGET == HWY_SCALAR
using DD = hn::Rebind<double, DF>;
HWY_INLINE hn::Vec<DD> WidenedPairSums(VF v) { return hn::PromoteTo(DD(), v); }
#else
using DD = hn::Rebind<double, hn::Half<DF>>;
HWY_INLINE hn::Vec<DD> WidenedPairSums(VF v) {
  const hn::Half<DF> dh;
  return hn::Add(hn::PromoteTo(DD(), hn::LowerHalf(dh, v)), hn::PromoteTo(DD(), hn::UpperHalf(dh, v)));
}
#endif
using VD = hn::Vec<DD>;

// One moment's running float sums, per channel. Named locals of this type (not an array of
// vectors, which GCC keeps on the stack) stay in registers: 15 of 32 with AVX-512.
struct ChannelSums {
  VF red, green, blue;
};

HWY_INLINE void Accumulate(VF term, VF red, VF green, VF blue, ChannelSums& sums) {
  sums.red = hn::MulAdd(term, red, sums.red);
  sums.green = hn::MulAdd(term, green, sums.green);
  sums.blue = hn::MulAdd(term, blue, sums.blue);
}

using LaneSums = double[kSums][kMaxFloatLanes];

// Adds the moments of row y (face coordinate t) of one face into `face` (double lanes, kSums per
// power of t). `row` is scratch, written before it is read.
void AddRowMoments(const float* HWY_RESTRICT rgb, const RowWeights& weights, int size, double t,
                   LaneSums& HWY_RESTRICT row, LaneSums* HWY_RESTRICT face) {
  const DF df;
  const DD dd;
  const int lanes = static_cast<int>(hn::Lanes(df));
  const VF one = hn::Set(df, 1.0f);
  const VF texel_width = hn::Set(df, 2.0f / static_cast<float>(size));
  const VF lane_step = hn::Set(df, static_cast<float>(lanes));
  VF centre = hn::Iota(df, 0.5f);  // x + 0.5 for each lane's texel x
  const int block_texels = kTermsPerLane * lanes;
  for (int begin = 0; begin < size; begin += block_texels) {
    const int end = std::min(size, begin + block_texels);
    const VF zero = hn::Zero(df);
    ChannelSums m0{zero, zero, zero}, m1 = m0, m2 = m0, m3 = m0, m4 = m0;
    auto add_texels = [&](const float* HWY_RESTRICT texels, const float* q_row, const float* qr_row,
                          const float* qr2_row) HWY_ATTR {
      VF red, green, blue;
      hn::LoadInterleaved3(df, texels, red, green, blue);
      const VF q = hn::LoadU(df, q_row);
      const VF qr = hn::LoadU(df, qr_row);
      const VF qr2 = hn::LoadU(df, qr2_row);
      const VF s = hn::Sub(hn::Mul(centre, texel_width), one);  // exact for power-of-two sizes
      centre = hn::Add(centre, lane_step);
      Accumulate(q, red, green, blue, m0);
      Accumulate(qr, red, green, blue, m1);
      Accumulate(hn::Mul(qr, s), red, green, blue, m2);
      Accumulate(qr2, red, green, blue, m3);
      Accumulate(hn::Mul(qr2, s), red, green, blue, m4);
    };
    int x = begin;
    for (; x + lanes <= end; x += lanes) add_texels(rgb + 3 * x, weights.q + x, weights.qr + x, weights.qr2 + x);
    if (x < end) {
      // The row is shorter than a vector: the missing texels get radiance 0 and weights 0, and
      // their (finite) s adds nothing.
      HWY_ALIGN float rgb_tail[3 * kMaxFloatLanes] = {};
      HWY_ALIGN float tails[3][kMaxFloatLanes] = {};
      std::copy(rgb + 3 * x, rgb + 3 * end, rgb_tail);
      std::copy(weights.q + x, weights.q + end, tails[0]);
      std::copy(weights.qr + x, weights.qr + end, tails[1]);
      std::copy(weights.qr2 + x, weights.qr2 + end, tails[2]);
      add_texels(rgb_tail, tails[0], tails[1], tails[2]);
    }
    int i = 0;
    for (const ChannelSums* m : {&m0, &m1, &m2, &m3, &m4}) {
      for (VF v : {m->red, m->green, m->blue}) {
        const VD widened = WidenedPairSums(v);
        hn::Store(begin == 0 ? widened : hn::Add(hn::Load(dd, row[i]), widened), dd, row[i]);
        ++i;
      }
    }
  }
  const VD powers[3] = {hn::Set(dd, 1.0), hn::Set(dd, t), hn::Set(dd, t * t)};
  for (int p = 0; p < 3; ++p) {
    for (int i = 0; i < kSums; ++i) {
      hn::Store(hn::MulAdd(powers[p], hn::Load(dd, row[i]), hn::Load(dd, face[p][i])), dd, face[p][i]);
    }
  }
}

void CubeMoments(const CubeTexels& faces, const FaceWeights& weights, int size, CubeMomentSums& out) {
  const DD dd;
  // Row by row across the six faces, so that each row of weights is read from memory once.
  HWY_ALIGN LaneSums sums[kFaces][3] = {};
  HWY_ALIGN LaneSums row_scratch = {};
  for (int y = 0; y < size; ++y) {
    const std::size_t offset = static_cast<std::size_t>(y) * size;
    const RowWeights row{weights.q + offset, weights.qr + offset, weights.qr2 + offset};
    const double t = 2.0 * (y + 0.5) / size - 1.0;
    for (int f = 0; f < kFaces; ++f) AddRowMoments(faces[f] + 3 * offset, row, size, t, row_scratch, sums[f]);
  }
  for (int f = 0; f < kFaces; ++f) {
    for (int p = 0; p < 3; ++p) {
      for (int i = 0; i < kSums; ++i) {
        double sum = 0.0;
        for (std::size_t j = 0; j < hn::Lanes(dd); ++j) sum += sums[f][p][i][j];
        out[f][p][i] = sum;
      }
    }
  }
}

using BlockLaneSums = double[kBlockMoments * 3][kMaxFloatLanes];

// Adds the products of texels [begin, end) of one face (at most kTermsPerLane vectors of them) and
// their block weights into `face` (double lanes, [moment * 3 + channel]).
void AddBlockMoments(const float* HWY_RESTRICT rgb, const BlockWeights& weights, std::size_t begin, std::size_t end,
                     BlockLaneSums& HWY_RESTRICT face) {
  const DF df;
  const DD dd;
  const std::size_t lanes = hn::Lanes(df);
  const VF zero = hn::Zero(df);
  ChannelSums m0{zero, zero, zero}, m1 = m0, m2 = m0, m3 = m0, m4 = m0, m5 = m0, m6 = m0, m7 = m0, m8 = m0;
  auto add_texels = [&](const float* HWY_RESTRICT texels, const BlockWeights& w, std::size_t x) HWY_ATTR {
    VF red, green, blue;
    hn::LoadInterleaved3(df, texels, red, green, blue);
    Accumulate(hn::LoadU(df, w[0] + x), red, green, blue, m0);
    Accumulate(hn::LoadU(df, w[1] + x), red, green, blue, m1);
    Accumulate(hn::LoadU(df, w[2] + x), red, green, blue, m2);
    Accumulate(hn::LoadU(df, w[3] + x), red, green, blue, m3);
    Accumulate(hn::LoadU(df, w[4] + x), red, green, blue, m4);
    Accumulate(hn::LoadU(df, w[5] + x), red, green, blue, m5);
    Accumulate(hn::LoadU(df, w[6] + x), red, green, blue, m6);
    Accumulate(hn::LoadU(df, w[7] + x), red, green, blue, m7);
    Accumulate(hn::LoadU(df, w[8] + x), red, green, blue, m8);
  };
  std::size_t x = begin;
  for (; x + lanes <= end; x += lanes) add_texels(rgb + 3 * x, weights, x);
  if (x < end) {
    // A texel count that is not a whole number of vectors: the missing texels get radiance 0 and
    // weights 0. (Powers of two never leave one: faces under a vector go to SmallCubeBlockMoments.)
    HWY_ALIGN float rgb_tail[3 * kMaxFloatLanes] = {};
    HWY_ALIGN float tails[kBlockMoments][kMaxFloatLanes] = {};
    std::copy(rgb + 3 * x, rgb + 3 * end, rgb_tail);
    BlockWeights tail_weights;
    for (int j = 0; j < kBlockMoments; ++j) {
      std::copy(weights[j] + x, weights[j] + end, tails[j]);
      tail_weights[j] = tails[j];
    }
    add_texels(rgb_tail, tail_weights, 0);
  }
  int i = 0;
  for (const ChannelSums* m : {&m0, &m1, &m2, &m3, &m4, &m5, &m6, &m7, &m8}) {
    for (VF v : {m->red, m->green, m->blue}) {
      const VD widened = WidenedPairSums(v);
      hn::Store(begin == 0 ? widened : hn::Add(hn::Load(dd, face[i]), widened), dd, face[i]);
      ++i;
    }
  }
}

// CubeBlockMoments for faces of fewer texels than a vector has lanes (1 x 1 and 2 x 2): the same
// float terms, added in double one at a time, without the vectors' padding.
void SmallCubeBlockMoments(const CubeTexels& faces, const BlockWeights& weights, int size, CubeMomentSums& out) {
  const std::size_t texels = static_cast<std::size_t>(size) * size;
  for (int f = 0; f < kFaces; ++f) {
    out[f] = {};
    for (int j = 0; j < kBlockMoments; ++j) {
      double* sums = &out[f][kBlockMomentSlots[j].power_of_t][3 * kBlockMomentSlots[j].moment];
      for (std::size_t x = 0; x < texels; ++x) {
        for (int c = 0; c < 3; ++c) sums[c] += static_cast<double>(weights[j][x] * faces[f][3 * x + c]);
      }
    }
  }
}

void CubeBlockMoments(const CubeTexels& faces, const BlockWeights& weights, int size, CubeMomentSums& out) {
  const DF df;
  const DD dd;
  const std::size_t texels = static_cast<std::size_t>(size) * size;
  const std::size_t block_texels = kTermsPerLane * hn::Lanes(df);
  if (texels < hn::Lanes(df)) return SmallCubeBlockMoments(faces, weights, size, out);
  // Block by block across the six faces, so that each block of weights is read from memory once.
  // AddBlockMoments stores the first block's sums and adds the others.
  HWY_ALIGN BlockLaneSums sums[kFaces];
  for (std::size_t begin = 0; begin < texels; begin += block_texels) {
    const std::size_t end = std::min(texels, begin + block_texels);
    for (int f = 0; f < kFaces; ++f) AddBlockMoments(faces[f], weights, begin, end, sums[f]);
  }
  for (int f = 0; f < kFaces; ++f) {
    out[f] = {};
    for (int j = 0; j < kBlockMoments; ++j) {
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (std::size_t lane = 0; lane < hn::Lanes(dd); ++lane) sum += sums[f][3 * j + c][lane];
        out[f][kBlockMomentSlots[j].power_of_t][3 * kBlockMomentSlots[j].moment + c] = sum;
      }
    }
  }
}

#if HWY_TARGET != HWY_SCALAR
// Halving without de-interleaving. A group of 2 L texels of a row (L = lanes) is six vectors of
// interleaved floats; with each vector added to itself shifted by three floats (the next texel's
// same channel), float p = 6 X + c (c < 3) holds texel pair X's sum of channel c. Output vector k of
// the group (texels k L / 3 ..) takes its L floats from those positions of at most three of the six
// vectors: kHalvingSources[k] names them, and per source a lane table and a lane mask say which
// output lanes come from where. The same for any L >= 4 (SSE4, AVX2, AVX-512).
constexpr int kHalvingVectorsIn = 6;
constexpr int kHalvingVectorsOut = 3;
struct HalvingSource {
  int output;  // output vector of the group
  int input;   // input vector of the group
};
constexpr HalvingSource kHalvingSources[] = {{0, 0}, {0, 1}, {1, 1}, {1, 2}, {1, 3}, {2, 3}, {2, 4}, {2, 5}};
constexpr int kHalvingSourceCount = sizeof(kHalvingSources) / sizeof(kHalvingSources[0]);

struct HalvingTables {
  int32_t lane[kHalvingSourceCount][kMaxFloatLanes];  // input lane of each output lane (0 if not taken)
  int32_t take[kHalvingSourceCount][kMaxFloatLanes];  // 1 where the output lane comes from this source
  int32_t three_on[kMaxFloatLanes];                   // lane l + 3 (0 for the last three lanes)
};

constexpr HalvingTables MakeHalvingTables(int lanes) {
  HalvingTables tables{};
  for (int l = 0; l + 3 < lanes; ++l) tables.three_on[l] = l + 3;
  for (int n = 0; n < kHalvingSourceCount; ++n) {
    for (int l = 0; l < lanes; ++l) {
      const int j = kHalvingSources[n].output * lanes + l;  // output float of the group
      const int p = 6 * (j / 3) + j % 3;                    // its pair sum's input float
      if (p / lanes == kHalvingSources[n].input) {
        tables.lane[n][l] = p % lanes;
        tables.take[n][l] = 1;
      }
    }
  }
  return tables;
}

#endif

// HalveRowPair, and with `copy_upper` / `copy_lower` not null, CopyAndHalveRowPair: each float of
// the two rows is stored there from the same load that the halving adds.
void HalveRows(const float* HWY_RESTRICT upper, const float* HWY_RESTRICT lower, float* HWY_RESTRICT out,
               int out_width, float* HWY_RESTRICT copy_upper, float* HWY_RESTRICT copy_lower) {
  int x = 0;
#if HWY_TARGET != HWY_SCALAR
  const DF df;
  const hn::RebindToSigned<DF> di;
  constexpr int kLanes = static_cast<int>(hn::MaxLanes(DF()));
  static_assert(kLanes >= 4, "the halving tables assume at least four float lanes");
  static constexpr HalvingTables kTables = MakeHalvingTables(kLanes);
  using Indices = decltype(hn::SetTableIndices(df, kTables.lane[0]));
  Indices lanes_of[kHalvingSourceCount];
  hn::Mask<DF> takes[kHalvingSourceCount];
  for (int n = 0; n < kHalvingSourceCount; ++n) {
    lanes_of[n] = hn::SetTableIndices(df, kTables.lane[n]);
    takes[n] = hn::RebindMask(df, hn::Eq(hn::LoadU(di, kTables.take[n]), hn::Set(di, 1)));
  }
  const VF quarter = hn::Set(df, 0.25f);
  const Indices three_on = hn::SetTableIndices(df, kTables.three_on);
  // Vector v of a group shifted by three floats (the next texel). The last vector of a row's last
  // group is shifted in registers rather than loaded, which would read past the row; the three
  // lanes that would come from past it are pair sums the halving does not take.
  auto shifted = [&](const float* row, VF vector, int v, bool last_group) HWY_ATTR {
    if (last_group && v == kHalvingVectorsIn - 1) return hn::TableLookupLanes(vector, three_on);
    return hn::LoadU(df, row + v * kLanes + 3);
  };
  // The group of 2 L texels at `up` and `down` into L texels at `to`, its floats copied to `up_copy`
  // and `down_copy` when those are not null.
  auto halve_group = [&](const float* HWY_RESTRICT up, const float* HWY_RESTRICT down, float* HWY_RESTRICT to,
                         float* HWY_RESTRICT up_copy, float* HWY_RESTRICT down_copy, bool last_group) HWY_ATTR {
    VF sums[kHalvingVectorsIn];
    for (int v = 0; v < kHalvingVectorsIn; ++v) {
      const VF up_v = hn::LoadU(df, up + v * kLanes), down_v = hn::LoadU(df, down + v * kLanes);
      if (up_copy != nullptr) {
        hn::StoreU(up_v, df, up_copy + v * kLanes);
        hn::StoreU(down_v, df, down_copy + v * kLanes);
      }
      const VF top = hn::Add(hn::Mul(up_v, quarter), hn::Mul(shifted(up, up_v, v, last_group), quarter));
      const VF bottom = hn::Add(hn::Mul(down_v, quarter), hn::Mul(shifted(down, down_v, v, last_group), quarter));
      sums[v] = hn::Add(top, bottom);
    }
    VF outputs[kHalvingVectorsOut] = {hn::Zero(df), hn::Zero(df), hn::Zero(df)};
    for (int n = 0; n < kHalvingSourceCount; ++n) {
      VF& output = outputs[kHalvingSources[n].output];
      output = hn::IfThenElse(takes[n], hn::TableLookupLanes(sums[kHalvingSources[n].input], lanes_of[n]), output);
    }
    for (int k = 0; k < kHalvingVectorsOut; ++k) hn::StoreU(outputs[k], df, to + k * kLanes);
  };
  auto copy_at = [](float* copy, int texel) { return copy == nullptr ? nullptr : copy + 3 * texel; };
  for (; x + kLanes <= out_width; x += kLanes) {
    halve_group(upper + 6 * x, lower + 6 * x, out + 3 * x, copy_at(copy_upper, 2 * x), copy_at(copy_lower, 2 * x),
                x + kLanes == out_width);
  }
#endif
  if (copy_upper != nullptr) {
    std::copy(upper + 6 * x, upper + 6 * out_width, copy_upper + 6 * x);
    std::copy(lower + 6 * x, lower + 6 * out_width, copy_lower + 6 * x);
  }
  for (; x < out_width; ++x) {
    for (int c = 0; c < 3; ++c) {
      const float top = upper[6 * x + c] * 0.25f + upper[6 * x + 3 + c] * 0.25f;
      const float bottom = lower[6 * x + c] * 0.25f + lower[6 * x + 3 + c] * 0.25f;
      out[3 * x + c] = top + bottom;
    }
  }
}

void HalveRowPair(const float* HWY_RESTRICT upper, const float* HWY_RESTRICT lower, float* HWY_RESTRICT out,
                  int out_width) {
  HalveRows(upper, lower, out, out_width, nullptr, nullptr);
}

void CopyAndHalveRowPair(const float* HWY_RESTRICT upper, const float* HWY_RESTRICT lower, float* HWY_RESTRICT copy_upper,
                         float* HWY_RESTRICT copy_lower, float* HWY_RESTRICT out, int out_width) {
  HalveRows(upper, lower, out, out_width, copy_upper, copy_lower);
}

}  // namespace HWY_NAMESPACE
}  // namespace vs11::irradiance::kernels
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace vs11::irradiance::kernels {

HWY_EXPORT(CubeMoments);
HWY_EXPORT(CubeBlockMoments);
HWY_EXPORT(HalveRowPair);
HWY_EXPORT(CopyAndHalveRowPair);

void CubeMoments(const CubeTexels& faces, const FaceWeights& weights, int size, CubeMomentSums& out) {
  HWY_DYNAMIC_DISPATCH(CubeMoments)(faces, weights, size, out);
}

void CubeBlockMoments(const CubeTexels& faces, const BlockWeights& weights, int size, CubeMomentSums& out) {
  HWY_DYNAMIC_DISPATCH(CubeBlockMoments)(faces, weights, size, out);
}

void HalveRowPair(const float* upper, const float* lower, float* out, int out_width) {
  HWY_DYNAMIC_DISPATCH(HalveRowPair)(upper, lower, out, out_width);
}

void CopyAndHalveRowPair(const float* upper, const float* lower, float* copy_upper, float* copy_lower, float* out,
                         int out_width) {
  HWY_DYNAMIC_DISPATCH(CopyAndHalveRowPair)(upper, lower, copy_upper, copy_lower, out, out_width);
}

}  // namespace vs11::irradiance::kernels
#endif  // HWY_ONCE
