// How an instruction reads its sources and writes its destination, written once (§3.1): fetch every
// source (register, then swizzle, then negation) before the result is stored through the write mask,
// so that `add r0, r0.yzwx, r0` reads the old r0. The reference engine runs these templates on floats
// (one vertex); vm/ir/record.cc runs them on graph values, and so builds the IR from the same rules.
// An engine supplies only where a register's value lives, as a machine type M:
//
//   using Float = ...;                         // the lane type (float, a recorded value)
//   using Vec4 = std::array<Float, 4>;
//   Vec4 ReadConstant(long index, bool relative, int lane) const;  // c[index] or c[a0.<lane> + index]
//   Vec4 ReadInput(long index) const;                     // v#, index < kInputRegisterCount
//   int TempCount() const;                                // r0 .. r(TempCount() - 1) exist
//   Vec4& Temp(long index);  const Vec4& Temp(long index) const;  // index < TempCount()
//   Vec4& Output(int slot);                               // an OutputSlot
//   void WriteAddress(int lane, Float x);                 // mov/mova a0.<lane>, x (see AddressFromFloat)
//   Vec4 Zero() const;                                    // what unreadable registers read
// and, to run the straight-line programs batch and jit make of a later model's dynamic flow
// (vm/core/static_flow.h: setp, predicated writes, predicate registers p0, p1, ... as 1/0 lanes):
//   Vec4& Predicate(long index);  const Vec4& Predicate(long index) const;
//   Float AddressValue(int lane) const;                   // the float last written to a0.<lane> (0 before)
//   Float Written(Float old) const;                       // a lane's value before a predicated write
// A vs_1_1 machine has r0-r11 and reads and writes a0.x only (the lane is ignored); a straight-line
// program specialised from a later model (kLaterModelStraightLine) gets r0-r31 and a0's four lanes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <type_traits>

#include "vm/core/isa.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"
#include "vm/core/semantics.h"

namespace vs11::semantics {

// The version token of a straight-line program that vm/core/static_flow.h specialised from a later
// model. It is no model's token, so the program reads as vs_1_1 (Program::model) everywhere but in the
// registers the engines give it: the later models' r0-r31 and the four lanes of a0, where a vs_1_1
// program has r0-r11 and a0.x.
inline constexpr std::uint32_t kLaterModelStraightLine = 0xFFFE02FFu;
static_assert(!ShaderModelOfVersion(kLaterModelStraightLine));
inline constexpr int kLaterModelTempCount = RegisterCount(RegisterFile::kTemp, ShaderModel::kVs30);
inline bool HasLaterModelRegisters(const Program& program) { return program.version == kLaterModelStraightLine; }
inline int TempCountOf(const Program& program) {
  return HasLaterModelRegisters(program) ? kLaterModelTempCount : kTempRegisterCount;
}
inline int AddressLaneCountOf(const Program& program) { return HasLaterModelRegisters(program) ? 4 : 1; }

// a0.x = floor(x) (§1.5). NaN and values beyond +-2^20 become +-2^20, which puts every relative read
// out of range, so it reads 0 (the bank holds at most 2048 registers).
inline constexpr int kAddressLimit = 1 << 20;

// The tests run in this order so that a NaN fails both and lands on -kAddressLimit.
template <class V>
auto AddressFromFloat(V x) {
  const V whole = Floor(x);
  const V limit = Constant(x, static_cast<float>(kAddressLimit));
  const V below = IfThenElse(whole < limit, whole, limit);
  return ToInt(IfThenElse(whole > Constant(x, -static_cast<float>(kAddressLimit)), below,
                          Constant(x, -static_cast<float>(kAddressLimit))));
}

template <FloatRules kRules, class V>
V DotOfWidth(int width, const Vec4<V>& a, const Vec4<V>& b) {
  return width == 3 ? Dot<kRules, V, 3>(a, b) : Dot<kRules, V, 4>(a, b);
}

template <class M>
concept HasPredicates = requires(M& machine) { machine.Predicate(0L); };

// Register `reg` + `row` (row > 0: the next registers of a matrix operand). Temporaries and inputs
// past the file, outputs and a0 read Zero() (the validator rejects such sources).
template <class M>
typename M::Vec4 ReadRegister(const M& machine, const RegisterRef& reg, int row) {
  const long index = static_cast<long>(reg.index) + row;
  switch (reg.file) {
    case RegisterFile::kConst: return machine.ReadConstant(index, reg.relative, reg.address.swizzle_bits & 3);
    case RegisterFile::kTemp: return index < machine.TempCount() ? machine.Temp(index) : machine.Zero();
    case RegisterFile::kInput: return index < kInputRegisterCount ? machine.ReadInput(index) : machine.Zero();
    case RegisterFile::kPredicate:
      if constexpr (HasPredicates<M>) return machine.Predicate(index);
      return machine.Zero();
    default: return machine.Zero();
  }
}

// A source operand's value: its register, swizzled, then _abs (vs_3_0), then negated when the operand
// says so (-r0_abs is -|r0|).
template <class M>
typename M::Vec4 FetchSource(const M& machine, const SourceOperand& source, int row) {
  const typename M::Vec4 base = ReadRegister(machine, source.reg, row);
  typename M::Vec4 value;
  for (int lane = 0; lane < 4; ++lane) {
    typename M::Float v = base[source.swizzle[lane]];
    if (source.absolute) v = Abs(v);
    value[lane] = source.negate ? Negate(v) : v;
  }
  return value;
}

// The lanes an instruction writes: its mask, less what the opcode never writes (crs's w, sincos's z
// and w, a matrix's missing rows), whatever mask an unvalidated program gives.
inline WriteMask LanesWritten(const Instruction& instruction) {
  std::uint8_t lanes = instruction.dest.mask.bits();
  if (instruction.opcode == Opcode::kCrs) lanes &= kLanesXyz;
  if (instruction.opcode == Opcode::kSincos) lanes &= kLanesXy;
  lanes &= static_cast<std::uint8_t>((1u << instruction.info().result_lanes()) - 1);
  return WriteMask(lanes);
}

// Writes the lanes of `value` that `lanes` selects; a predicated instruction's lanes only where its
// predicate holds (PredicatedWrite).
template <class M>
void StoreDest(M& machine, const Instruction& instruction, const typename M::Vec4& value, WriteMask lanes) {
  const DestOperand& dest = instruction.dest;
  typename M::Vec4 guard{};
  bool predicated = false;
  if constexpr (HasPredicates<M>) {
    predicated = instruction.predicated;
    if (predicated) guard = FetchSource(machine, instruction.predicate, 0);
  }
  const auto written = [&](typename M::Float old, int lane) {
    if constexpr (HasPredicates<M>) {
      if (predicated) return PredicatedWrite(guard[lane], instruction.predicate.logical_not, value[lane], machine.Written(old));
    }
    return value[lane];
  };
  if (dest.reg.file == RegisterFile::kAddress) {
    for (int lane = 0; lane < 4; ++lane) {
      if (!lanes.has(lane)) continue;
      if constexpr (HasPredicates<M>) {
        if (predicated) {
          machine.WriteAddress(lane, written(machine.AddressValue(lane), lane));
          continue;
        }
      }
      machine.WriteAddress(lane, value[lane]);
    }
    return;
  }
  typename M::Vec4* target = nullptr;
  if (dest.reg.file == RegisterFile::kTemp) {
    if (dest.reg.index < machine.TempCount()) target = &machine.Temp(dest.reg.index);
  } else if (dest.reg.file == RegisterFile::kPredicate) {
    if constexpr (HasPredicates<M>) target = &machine.Predicate(dest.reg.index);
  } else if (std::optional<int> slot = OutputSlotOf(dest.reg)) {
    target = &machine.Output(*slot);
  }
  if (target == nullptr) return;
  for (int lane = 0; lane < 4; ++lane) {
    if (lanes.has(lane)) (*target)[lane] = written((*target)[lane], lane);
  }
}

// One instruction on `machine`: Semantics is the row's kernel (<Name>Semantics in semantics.h), its
// products under kRules.
template <class Semantics, FloatRules kRules, class M>
void Execute(M& machine, const Instruction& instruction) {
  using Float = typename M::Float;
  using Vec4F = typename M::Vec4;
  const OpcodeInfo& info = instruction.info();
  std::array<Vec4F, 3> src{};
  for (int s = 0; s < info.source_count(); ++s) src[s] = FetchSource(machine, instruction.sources[s], 0);
  Vec4F result{};
  if constexpr (std::is_same_v<Semantics, SetpSemantics>) {
    for (int lane = 0; lane < 4; ++lane) result[lane] = Compare(instruction.comparison, src[0][lane], src[1][lane]);
  } else if constexpr (HasLane<Semantics, Float>) {
    for (int lane = 0; lane < 4; ++lane) {
      result[lane] = RunLane<kRules, Semantics>(src[0][lane], src[1][lane], src[2][lane]);
    }
  } else if constexpr (HasScalar<Semantics, Float>) {
    result.fill(Semantics::Scalar(src[0][3]));
  } else if constexpr (HasVector<Semantics, Float>) {
    result = RunVector<kRules, Semantics>(src[0], src[1]);
  } else if (info.kind == ResultKind::kDotProduct) {
    result.fill(DotOfWidth<kRules>(info.dot_width, src[0], src[1]));
  } else if (info.kind == ResultKind::kMatrix) {
    for (int row = 0; row < info.matrix_rows; ++row) {
      result[row] = DotOfWidth<kRules>(info.dot_width, src[0],
                               FetchSource(machine, instruction.sources[OpcodeInfo::kMatrixSource], row));
    }
  } else {
    return;  // nop, dcl, def
  }
  if (instruction.dest.saturate) {
    for (Float& v : result) v = Saturate(v);
  }
  StoreDest(machine, instruction, result, LanesWritten(instruction));
}

// The one opcode dispatch: `instruction` on `machine` with its row's kernel. The reference engine runs
// it on floats, vm/ir/record.cc on graph values (which the jit and the translator read).
template <FloatRules kRules, class M>
void ExecuteInstruction(M& machine, const Instruction& instruction) {
  switch (instruction.opcode) {
#define VS11_EXECUTE_CASE(name, ...) \
  case Opcode::k##name: Execute<name##Semantics, kRules>(machine, instruction); break;
    VS11_OPCODES(VS11_EXECUTE_CASE)
#undef VS11_EXECUTE_CASE
  }
}

}  // namespace vs11::semantics
