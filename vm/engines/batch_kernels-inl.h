// The batch engine's kernels for one Highway target (the one HWY_TARGET names), included by exactly
// one vm/engines/batch_kernels_<target>.cc. Each kernel runs one Step (vm/engines/batch_plan.h) over
// every vertex of a batch, with the arithmetic of vm/core/semantics.h instantiated for the target's float vector, and the
// target's KernelTable is returned by GetKernelTable().
//
// Bit exactness: the kernels add nothing to the shared arithmetic. Negation is Highway's Neg (a sign
// flip, as scalar -x), loads and stores move bits unchanged, dot products use semantics::Dot (left to
// right), and the build has -ffp-contract=off so a*b+c is never fused.

#ifndef VS11_VM_BATCH_KERNELS_INL_H_
#define VS11_VM_BATCH_KERNELS_INL_H_

// Why one translation unit per target instead of hwy/foreach_target.h: GCC compiles a template for
// the target in force where the template is *defined*, and the semantics kernels call Highway's
// always-inline, target-specific ops. vm/core/semantics.h must therefore be defined under this target's
// `#pragma GCC target`, which with its `#pragma once` means a translation unit of its own. Each
// vm/engines/batch_kernels_<target>.cc sets HWY_TARGET and includes this file; vm/engines/batch_engine.cc
// dispatches to them with HWY_EXPORT / HWY_DYNAMIC_DISPATCH. The Standard Library and the engine's
// own headers are included first, outside the target pragma, so that only vm/core/semantics.h and the
// kernels below are compiled for the target (and its float overloads, which would be ODR-shared
// with the reference engine, are never used outside the scalar target).
#ifndef HWY_TARGET
#error "define HWY_TARGET before including vm/engines/batch_kernels-inl.h"
#endif

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "hwy/highway.h"
#include "vm/engines/batch_plan.h"

HWY_BEFORE_NAMESPACE();
#include "vm/core/semantics.h"  // NOLINT(build/include_order): must follow the target pragma
#include "vm/core/constant_gather.h"  // NOLINT(build/include_order): likewise
#include "vm/core/texture_sampling.h"  // NOLINT(build/include_order): likewise

// The lane operations vm/core/semantics.h calls that Highway lacks or names differently. The kernels call
// them unqualified from namespace vs11::semantics, so they must sit where argument-dependent lookup
// looks for a Highway vector: Highway's per-target namespace, next to its own Floor, Sqrt, IfThenElse.
namespace hwy {
namespace HWY_NAMESPACE {

template <class V, HWY_IF_FLOAT_V(V)>
HWY_API V Constant(V /*like*/, float value) {
  return Set(DFromV<V>(), value);
}
template <class V, HWY_IF_FLOAT_V(V)>
HWY_API Vec<RebindToSigned<DFromV<V>>> ConstantInt(V /*like*/, int32_t value) {
  return Set(RebindToSigned<DFromV<V>>(), value);
}
template <class V, HWY_IF_FLOAT_V(V)>
HWY_API Vec<RebindToSigned<DFromV<V>>> BitsOf(V v) {
  return BitCast(RebindToSigned<DFromV<V>>(), v);
}
template <class VI, HWY_IF_SIGNED_V(VI)>
HWY_API Vec<RebindToFloat<DFromV<VI>>> FloatFromBits(VI bits) {
  return BitCast(RebindToFloat<DFromV<VI>>(), bits);
}
// Truncates; the kernels only convert integral values well inside int32 range.
template <class V, HWY_IF_FLOAT_V(V)>
HWY_API Vec<RebindToSigned<DFromV<V>>> ToInt(V v) {
  return ConvertTo(RebindToSigned<DFromV<V>>(), v);
}
template <class VI, HWY_IF_SIGNED_V(VI)>
HWY_API Vec<RebindToFloat<DFromV<VI>>> ToFloat(VI v) {
  return ConvertTo(RebindToFloat<DFromV<VI>>(), v);
}

// Flips the sign bit, as scalar -x (mova's kernel and the negate source modifier). The empty asm keeps
// the compiler from folding a + (-b) into a - b (clang does), which would return b's NaN unflipped
// where the reference engine flips it.
template <class V, HWY_IF_FLOAT_V(V)>
HWY_API V Negate(V value) {
  V negated = Neg(value);
#if HWY_ARCH_X86 && HWY_TARGET != HWY_EMU128 && HWY_TARGET != HWY_SCALAR
  asm("" : "+v"(negated.raw));
#endif
  return negated;
}

#if HWY_TARGET == HWY_SSSE3 || HWY_TARGET == HWY_EMU128
// These targets have no roundps, and Highway's emulated Floor returns +0 for -0 where IEEE floor
// (std::floor, roundps) keeps the sign, so frc(-0) and expp(-0).y would differ from the reference
// engine. floor(x) always carries the sign of x, so copying the sign back fixes every input. As a
// non-template this overload beats Highway's template for the full vectors the kernels use.
HWY_API Vec128<float> Floor(Vec128<float> v) { return CopySign(Floor<float, 4>(v), v); }
#endif

}  // namespace HWY_NAMESPACE
}  // namespace hwy

namespace vs11::batch {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Vector access for the kernels below.
#if HWY_TARGET == HWY_SCALAR
// Highway's HWY_SCALAR Floor also returns +0 for -0, and it cannot be overloaded as above; this
// target (the fallback when GCC < 12.3 makes EMU128 unsafe) therefore runs the semantics on plain
// float, the reference engine's own instantiation, one vertex per iteration.
using VF = float;
HWY_INLINE std::size_t LanesPerVector() { return 1; }
HWY_INLINE VF Broadcast(float value) { return value; }
HWY_INLINE VF LoadLanes(const float* from) { return *from; }
HWY_INLINE void StoreLanes(VF value, float* to) { *to = value; }
// The empty asm keeps GCC from folding -a + b into b - a, which would lose the sign flip of a NaN
// (the reference engine negates while fetching, before the arithmetic).
HWY_INLINE VF Negate(VF value) {
  VF negated = -value;
  asm("" : "+x"(negated));
  return negated;
}
#else
using D = hn::ScalableTag<float>;
using VF = hn::Vec<D>;
HWY_INLINE std::size_t LanesPerVector() { return hn::Lanes(D()); }
HWY_INLINE VF Broadcast(float value) { return hn::Set(D(), value); }
HWY_INLINE VF LoadLanes(const float* from) { return hn::LoadU(D(), from); }
HWY_INLINE void StoreLanes(VF value, float* to) { hn::StoreU(value, D(), to); }
using hn::Negate;
#endif
using Vec4F = semantics::Vec4<VF>;
static_assert(kVertexGranule * sizeof(float) % HWY_MAX_BYTES == 0, "a batch must be whole vectors");

// Loads one source operand, the way fixed by K, so that the vertex loop has no branch. Made
// directly from the step (no default state), so setting a kernel up costs a few scalar loads.
template <OperandKind K>
struct OperandReader {
  HWY_INLINE OperandReader(const Frame& frame, const Operand& operand, bool negate) {
    if constexpr (K == OperandKind::kBroadcast) {
      const float value = frame.constants[operand.index];
      broadcast = Broadcast(negate ? -value : value);
    } else {
      lane = frame.read_lanes[operand.index];
    }
  }
  HWY_INLINE VF operator()(std::size_t i) const {
    if constexpr (K == OperandKind::kBroadcast) {
      return broadcast;
    } else if constexpr (K == OperandKind::kArray) {
      return LoadLanes(lane + i);
    } else {
      return Negate(LoadLanes(lane + i));
    }
  }

  const float* lane;
  VF broadcast;
};

// Readers for components 0..kCount-1 of `operands`.
template <OperandKind K, std::size_t... kIndex>
HWY_INLINE std::array<OperandReader<K>, sizeof...(kIndex)> MakeReaders(const Frame& frame,
                                                                       const std::array<Operand, 4>& operands,
                                                                       bool negate, std::index_sequence<kIndex...>) {
  return {OperandReader<K>(frame, operands[kIndex], negate)...};
}

// Loads an operand of any kind, deciding per call; for the rare vector ops only.
class AnyOperandReader {
 public:
  AnyOperandReader() = default;
  AnyOperandReader(const Frame& frame, const Operand& operand, bool negate) : negate_(negate) {
    if (operand.is_array) {
      lane_ = frame.read_lanes[operand.index];
    } else {
      const float value = frame.constants[operand.index];
      value_ = Broadcast(negate ? -value : value);
    }
  }
  HWY_INLINE VF operator()(std::size_t i) const {
    if (lane_ == nullptr) return value_;
    const VF loaded = LoadLanes(lane_ + i);
    return negate_ ? Negate(loaded) : loaded;
  }

 private:
  const float* lane_ = nullptr;
  bool negate_ = false;
  VF value_ = Broadcast(0.0f);
};

// kLanes lanes of a componentwise op: dest[l] = Lane(a[l], b[l], c[l]); unused sources are broadcast
// zeros. All loads of a vertex group come before its stores, so `add r0, r0.yzwx, r0` works in place.
template <class Semantics, FloatRules kRules, int kArity, OperandKind K0, OperandKind K1, OperandKind K2,
          std::size_t... kLane>
HWY_INLINE void ComponentwiseLanes(const Step& step, const Frame& frame, std::index_sequence<kLane...>) {
  constexpr std::size_t kLanes = sizeof...(kLane);
  const std::array<OperandReader<K0>, kLanes> a = {OperandReader<K0>(frame, step.sources[0][kLane], step.negate[0])...};
  const std::array<OperandReader<K1>, kLanes> b = {OperandReader<K1>(frame, step.sources[1][kLane], step.negate[1])...};
  const std::array<OperandReader<K2>, kLanes> c = {OperandReader<K2>(frame, step.sources[2][kLane], step.negate[2])...};
  float* const out[kLanes] = {frame.write_lanes[step.dest[kLane]]...};
  for (std::size_t i = 0; i < frame.count; i += LanesPerVector()) {
    VF result[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) {
      const VF va = a[l](i);
      const VF vb = kArity > 1 ? b[l](i) : va;
      const VF vc = kArity > 2 ? c[l](i) : va;
      result[l] = semantics::RunLane<kRules, Semantics>(va, vb, vc);
    }
    for (std::size_t l = 0; l < kLanes; ++l) StoreLanes(result[l], out[l] + i);
  }
}

template <class Semantics, FloatRules kRules, int kArity, int kLanes, OperandKind K0, OperandKind K1, OperandKind K2>
void LaneKernel(const Step& step, const Frame& frame) {
  ComponentwiseLanes<Semantics, kRules, kArity, K0, K1, K2>(step, frame, std::make_index_sequence<kLanes>());
}

template <class Semantics, OperandKind K>
void ScalarKernel(const Step& step, const Frame& frame) {
  const OperandReader<K> a(frame, step.sources[0][0], step.negate[0]);
  float* out = frame.write_lanes[step.dest[0]];
  for (std::size_t i = 0; i < frame.count; i += LanesPerVector()) {
    StoreLanes(Semantics::Scalar(a(i)), out + i);
  }
}

// kRows dot products of one vector with kRows row operands. Every load of a vertex group comes
// before its stores, so a row may write a lane another row (or the vector) reads.
template <FloatRules kRules, int kWidth, int kRows, OperandKind KVector, OperandKind KRow, std::size_t... kRow>
HWY_INLINE void DotRows(const Step& step, const Frame& frame, std::index_sequence<kRow...>) {
  using Components = std::make_index_sequence<kWidth>;
  const auto vector = MakeReaders<KVector>(frame, step.sources[0], step.negate[0], Components());
  const std::array<std::array<OperandReader<KRow>, kWidth>, kRows> rows = {
      MakeReaders<KRow>(frame, step.sources[1 + kRow], step.negate[1 + kRow], Components())...};
  float* const out[kRows] = {frame.write_lanes[step.dest[kRow]]...};
  for (std::size_t i = 0; i < frame.count; i += LanesPerVector()) {
    Vec4F a, b;
    for (int c = 0; c < kWidth; ++c) a[c] = vector[c](i);
    VF result[kRows];
    for (int r = 0; r < kRows; ++r) {
      for (int c = 0; c < kWidth; ++c) b[c] = rows[r][c](i);
      result[r] = semantics::Dot<kRules, VF, kWidth>(a, b);
    }
    for (int r = 0; r < kRows; ++r) StoreLanes(result[r], out[r] + i);
  }
}

template <FloatRules kRules, int kWidth, int kRows, OperandKind KVector, OperandKind KRow>
void DotKernel(const Step& step, const Frame& frame) {
  DotRows<kRules, kWidth, kRows, KVector, KRow>(step, frame, std::make_index_sequence<kRows>());
}

// lit, dst, expp, logp: whole vec4 in, masked vec4 out.
template <class Semantics, FloatRules kRules>
void VectorKernel(const Step& step, const Frame& frame) {
  std::array<std::array<AnyOperandReader, 4>, 2> sources;
  std::array<float*, 4> out{};
  for (int c = 0; c < 4; ++c) {
    for (int s = 0; s < 2; ++s) sources[s][c] = AnyOperandReader(frame, step.sources[s][c], step.negate[s]);
    if (step.dest[c] != kNoLane) out[c] = frame.write_lanes[step.dest[c]];
  }
  for (std::size_t i = 0; i < frame.count; i += LanesPerVector()) {
    Vec4F a, b;
    for (int c = 0; c < 4; ++c) {
      a[c] = sources[0][c](i);
      b[c] = sources[1][c](i);
    }
    const Vec4F result = semantics::RunVector<kRules, Semantics>(a, b);
    for (int c = 0; c < 4; ++c) {
      if (out[c] != nullptr) StoreLanes(result[c], out[c] + i);
    }
  }
}

// dest[c] = component c of c[a0.<address_lane> + base] per vertex; registers outside the bank read 0
// (row 0).
void GatherKernel(const Step& step, const Frame& frame) {
  const std::int32_t* address = frame.address + step.address_lane * kBatchSize;
  std::array<float*, 4> out{};
  for (int c = 0; c < 4; ++c) {
    if (step.dest[c] != kNoLane) out[c] = frame.write_lanes[step.dest[c]];
  }
#if HWY_TARGET == HWY_SCALAR
  const auto literal = [](std::int32_t value) { return value; };
  for (std::size_t i = 0; i < frame.count; ++i) {
    const std::int32_t offset = semantics::RelativeConstantOffset(address[i], step.base, frame.constant_count,
                                                                  kFirstConstantRow, literal);
    for (int c = 0; c < 4; ++c) {
      if (out[c] != nullptr) out[c][i] = frame.constants[offset + c];
    }
  }
#else
  const D d;
  const hn::RebindToSigned<D> di;
  const auto literal = [&di](std::int32_t value) { return hn::Set(di, value); };
  const auto count = literal(frame.constant_count);
  for (std::size_t i = 0; i < frame.count; i += hn::Lanes(d)) {
    const auto offset = semantics::RelativeConstantOffset(hn::LoadU(di, address + i), step.base, count,
                                                          kFirstConstantRow, literal);
    for (int c = 0; c < 4; ++c) {
      if (out[c] != nullptr) hn::StoreU(hn::GatherIndex(d, frame.constants + c, offset), d, out[c] + i);
    }
  }
#endif
}

// texldl's texture reader (vm/core/texture_sampling.h) over a batch: texels gathered per vertex.
struct FrameTextures {
  const TextureView* textures;
  HWY_INLINE TextureShape Shape(int sampler) const {
    return sampler >= 0 && sampler < kVertexSamplerCount ? textures[sampler].shape : TextureShape{};
  }
#if HWY_TARGET == HWY_SCALAR
  HWY_INLINE Vec4F Texel(int sampler, std::int32_t index) const {
    const TextureView& view = textures[sampler];
    const int channels = ChannelCount(view.shape.format);
    Vec4F texel{};
    for (int c = 0; c < channels; ++c) texel[c] = view.texels[static_cast<std::ptrdiff_t>(index) * channels + c];
    return texel;
  }
#else
  template <class VI>
  HWY_INLINE Vec4F Texel(int sampler, VI index) const {
    const D d;
    const TextureView& view = textures[sampler];
    const VF zero = hn::Zero(d);
    if (view.shape.format == TextureFormat::kR32F) return {hn::GatherIndex(d, view.texels, index), zero, zero, zero};
    const VI offset = hn::ShiftLeft<2>(index);
    return {hn::GatherIndex(d, view.texels, offset), hn::GatherIndex(d, view.texels + 1, offset),
            hn::GatherIndex(d, view.texels + 2, offset), hn::GatherIndex(d, view.texels + 3, offset)};
  }
#endif
};

// texldl: dest[c] = component sources[1][c].index of the sample at (sources[0][0], sources[0][1]).
void TextureKernel(const Step& step, const Frame& frame) {
  const AnyOperandReader u(frame, step.sources[0][0], step.negate[0]);
  const AnyOperandReader v(frame, step.sources[0][1], step.negate[0]);
  std::array<float*, 4> out{};
  for (int c = 0; c < 4; ++c) {
    if (step.dest[c] != kNoLane) out[c] = frame.write_lanes[step.dest[c]];
  }
  const FrameTextures reader{frame.textures};
  const VF zero = Broadcast(0.0f);
  for (std::size_t i = 0; i < frame.count; i += LanesPerVector()) {
    const Vec4F sample = semantics::SampleTexture(reader, step.base, Vec4F{u(i), v(i), zero, zero});
    for (int c = 0; c < 4; ++c) {
      if (out[c] != nullptr) StoreLanes(sample[step.sources[1][c].index], out[c] + i);
    }
  }
}

// ---- kernel table ----------------------------------------------------------------------------------

constexpr int PowerOfThree(int exponent) { return exponent == 0 ? 1 : 3 * PowerOfThree(exponent - 1); }

template <class Semantics, FloatRules kRules, int kArity, int kLanes, std::size_t... kIndex>
void FillLaneKernels(std::array<Kernel, 27>& row, std::index_sequence<kIndex...>) {
  ((row[kIndex] = &LaneKernel<Semantics, kRules, kArity, kLanes, static_cast<OperandKind>(kIndex % 3),
                              (kArity > 1 ? static_cast<OperandKind>(kIndex / 3 % 3) : OperandKind::kBroadcast),
                              (kArity > 2 ? static_cast<OperandKind>(kIndex / 9) : OperandKind::kBroadcast)>),
   ...);
}

template <class Semantics, FloatRules kRules, int kArity, std::size_t... kLanesMinusOne>
void FillLaneCounts(std::array<std::array<Kernel, 27>, 4>& rows, std::index_sequence<kLanesMinusOne...>) {
  (FillLaneKernels<Semantics, kRules, kArity, kLanesMinusOne + 1>(rows[kLanesMinusOne],
                                                                 std::make_index_sequence<PowerOfThree(kArity)>()),
   ...);
}

template <FloatRules kRules, int kWidth, int kRows, std::size_t... kIndex>
void FillDotKernels(std::array<Kernel, 9>& row, std::index_sequence<kIndex...>) {
  ((row[kIndex] = &DotKernel<kRules, kWidth, kRows, static_cast<OperandKind>(kIndex % 3),
                             static_cast<OperandKind>(kIndex / 3)>),
   ...);
}

// _sat as a componentwise kernel of one array source (the lanes it clamps in place).
struct SaturateLanes {
  template <class V> static V Lane(V a, V, V) { return semantics::Saturate(a); }
};

template <std::size_t... kLanesMinusOne>
void FillSaturateKernels(std::array<Kernel, 4>& kernels, std::index_sequence<kLanesMinusOne...>) {
  ((kernels[kLanesMinusOne] = &LaneKernel<SaturateLanes, FloatRules::kD3d9, 1, kLanesMinusOne + 1, OperandKind::kArray,
                                          OperandKind::kBroadcast, OperandKind::kBroadcast>),
   ...);
}

template <FloatRules kRules, int kWidth, std::size_t... kRowsMinusOne>
void FillDotWidth(std::array<std::array<Kernel, 9>, 4>& rows, std::index_sequence<kRowsMinusOne...>) {
  (FillDotKernels<kRules, kWidth, kRowsMinusOne + 1>(rows[kRowsMinusOne], std::make_index_sequence<9>()), ...);
}

// Picks the kernel family from the form of the opcode's semantics struct, as the reference engine's
// Execute does. A kernel that does not follow the float rules (no products) is compiled once, for
// d3d9, and kept by the tables of the other rules.
template <class Semantics, Opcode kOpcode, FloatRules kRules>
void FillOpcode(KernelTable& table) {
  constexpr int kIndex = static_cast<int>(kOpcode);
  if constexpr (kRules != FloatRules::kD3d9 && !semantics::FollowsFloatRules<Semantics>) {
    return;
  } else if constexpr (semantics::HasLane<Semantics, VF>) {
    constexpr int kArity = KernelArity(Info(kOpcode));
    FillLaneCounts<Semantics, kRules, kArity>(table.lane[kIndex], std::make_index_sequence<4>());
  } else if constexpr (semantics::HasScalar<Semantics, VF>) {
    table.scalar[kIndex] = {&ScalarKernel<Semantics, OperandKind::kArray>,
                            &ScalarKernel<Semantics, OperandKind::kNegatedArray>,
                            &ScalarKernel<Semantics, OperandKind::kBroadcast>};
  } else if constexpr (semantics::HasVector<Semantics, VF>) {
    table.vector[kIndex] = &VectorKernel<Semantics, kRules>;
  }
}

template <std::size_t... kComparisonMinusOne>
void FillCompareKernels(KernelTable& table, std::index_sequence<kComparisonMinusOne...>) {
  (FillLaneCounts<semantics::CompareSemantics<kComparisonMinusOne + 1>, FloatRules::kD3d9, 2>(
       table.compare[kComparisonMinusOne], std::make_index_sequence<4>()),
   ...);
}

// `table` holds the d3d9 kernels for every rule but d3d9; this fills in what differs.
template <FloatRules kRules>
KernelTable MakeKernelTable(KernelTable table) {
#define VS11_BATCH_FILL_OPCODE(name, ...) FillOpcode<semantics::name##Semantics, Opcode::k##name, kRules>(table);
  VS11_OPCODES(VS11_BATCH_FILL_OPCODE)
#undef VS11_BATCH_FILL_OPCODE
  FillDotWidth<kRules, 3>(table.dot[0], std::make_index_sequence<4>());
  FillDotWidth<kRules, 4>(table.dot[1], std::make_index_sequence<4>());
  table.gather = &GatherKernel;
  table.texture = &TextureKernel;
  FillSaturateKernels(table.saturate, std::make_index_sequence<4>());
  if constexpr (kRules == FloatRules::kD3d9) {  // masks and compares follow no float rules
    FillCompareKernels(table, std::make_index_sequence<6>());
    FillLaneCounts<semantics::PredicatedWriteSemantics<false>, kRules, 3>(table.predicated[0], std::make_index_sequence<4>());
    FillLaneCounts<semantics::PredicatedWriteSemantics<true>, kRules, 3>(table.predicated[1], std::make_index_sequence<4>());
  }
  return table;
}

const KernelTable* GetKernelTable(FloatRules rules) {
  static const KernelTable d3d9 = MakeKernelTable<FloatRules::kD3d9>(KernelTable());
  static const KernelTable legacy = MakeKernelTable<FloatRules::kLegacy>(d3d9);
  return rules == FloatRules::kLegacy ? &legacy : &d3d9;
}

}  // namespace HWY_NAMESPACE
}  // namespace vs11::batch

HWY_AFTER_NAMESPACE();

#endif  // VS11_VM_BATCH_KERNELS_INL_H_
