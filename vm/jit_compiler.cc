#include "vm/jit_compiler.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>

#include <xbyak/xbyak.h>
#include <xbyak/xbyak_util.h>

#include "vm/batch_plan.h"
#include "vm/machine.h"
#include "vm/reference_engine.h"
#include "vm/semantics.h"

namespace vs11::jit {
namespace {

// ---- the traced program: a graph of vector operations on one vector of vertices ---------------------

enum class Op : std::uint8_t {
  kInput,     // immediate: lane table index
  kConstant,  // immediate: constant table index (broadcast)
  kLiteral,   // immediate: the float's bits (broadcast)
  kAdd, kSub, kMul, kDiv, kFloor, kSqrt,
  kLess, kGreater, kGreaterEqual, kEqual, kUnordered,  // all-ones lanes where true
  kSelect,    // args: mask, yes, no
  kIntAdd, kIntSub, kAnd, kOr, kXor, kShiftLeft, kShiftRight,  // immediate: shift count
  kToInt, kToFloat,
  kIntGreater,     // all-ones lanes where a > b (signed)
  kConstantCount,  // RunArguments::constant_count (broadcast)
  kGather,         // args: constant table offset in floats; immediate: component (0..3)
  kStore,          // immediate: lane table index; args: value
};

constexpr int kNoArg = -1;

struct Node {
  Op op;
  std::array<int, 3> args = {kNoArg, kNoArg, kNoArg};
  std::uint32_t immediate = 0;
};

class Graph {
 public:
  // Identical pure nodes are made once (v0.x read by three dp4s is one load).
  int Add(Op op, std::array<int, 3> args = {kNoArg, kNoArg, kNoArg}, std::uint32_t immediate = 0) {
    if (op != Op::kStore) {
      const auto key = std::make_tuple(op, args, immediate);
      if (const auto it = existing_.find(key); it != existing_.end()) return it->second;
      existing_.emplace(key, static_cast<int>(nodes_.size()));
    }
    nodes_.push_back({op, args, immediate});
    return static_cast<int>(nodes_.size()) - 1;
  }
  const std::vector<Node>& nodes() const { return nodes_; }

 private:
  std::vector<Node> nodes_;
  std::map<std::tuple<Op, std::array<int, 3>, std::uint32_t>, int> existing_;
};

// The graph being traced (Compile sets it for its duration; tracing is single-threaded per call).
thread_local Graph* tracing = nullptr;

int Trace(Op op, int a = kNoArg, int b = kNoArg, int c = kNoArg, std::uint32_t immediate = 0) {
  return tracing->Add(op, {a, b, c}, immediate);
}

// The lane types vm/semantics.h is instantiated with: handles to graph nodes, typed so that float,
// integer and mask operations resolve as they do for float/int32/bool and Highway vectors.
struct Float {
  int id = kNoArg;
};
struct Int {
  int id = kNoArg;
};
struct Mask {
  int id = kNoArg;
};

inline Float operator+(Float a, Float b) { return {Trace(Op::kAdd, a.id, b.id)}; }
inline Float operator-(Float a, Float b) { return {Trace(Op::kSub, a.id, b.id)}; }
inline Float operator*(Float a, Float b) { return {Trace(Op::kMul, a.id, b.id)}; }
inline Float operator/(Float a, Float b) { return {Trace(Op::kDiv, a.id, b.id)}; }
inline Mask operator<(Float a, Float b) { return {Trace(Op::kLess, a.id, b.id)}; }
inline Mask operator>(Float a, Float b) { return {Trace(Op::kGreater, a.id, b.id)}; }
inline Mask operator>=(Float a, Float b) { return {Trace(Op::kGreaterEqual, a.id, b.id)}; }
inline Mask operator==(Float a, Float b) { return {Trace(Op::kEqual, a.id, b.id)}; }
inline Int operator+(Int a, Int b) { return {Trace(Op::kIntAdd, a.id, b.id)}; }
inline Int operator-(Int a, Int b) { return {Trace(Op::kIntSub, a.id, b.id)}; }
inline Int operator&(Int a, Int b) { return {Trace(Op::kAnd, a.id, b.id)}; }
inline Int operator|(Int a, Int b) { return {Trace(Op::kOr, a.id, b.id)}; }

inline Float Constant(Float, float value) { return {Trace(Op::kLiteral, kNoArg, kNoArg, kNoArg, std::bit_cast<std::uint32_t>(value))}; }
inline Int ConstantInt(Float, std::int32_t value) {
  return {Trace(Op::kLiteral, kNoArg, kNoArg, kNoArg, static_cast<std::uint32_t>(value))};
}
inline Int BitsOf(Float x) { return {x.id}; }
inline Float FloatFromBits(Int x) { return {x.id}; }
inline Float Floor(Float x) { return {Trace(Op::kFloor, x.id)}; }
inline Float Sqrt(Float x) { return {Trace(Op::kSqrt, x.id)}; }
inline Float Abs(Float x) { return FloatFromBits(BitsOf(x) & ConstantInt(x, 0x7FFFFFFF)); }
inline Mask IsNaN(Float x) { return {Trace(Op::kUnordered, x.id, x.id)}; }
inline Float IfThenElse(Mask condition, Float yes, Float no) { return {Trace(Op::kSelect, condition.id, yes.id, no.id)}; }
inline Int ToInt(Float x) { return {Trace(Op::kToInt, x.id)}; }
inline Float ToFloat(Int x) { return {Trace(Op::kToFloat, x.id)}; }
template <int kBits>
Int ShiftLeft(Int x) { return {Trace(Op::kShiftLeft, x.id, kNoArg, kNoArg, kBits)}; }
template <int kBits>
Int ShiftRight(Int x) { return {Trace(Op::kShiftRight, x.id, kNoArg, kNoArg, kBits)}; }
inline Mask operator>(Int a, Int b) { return {Trace(Op::kIntGreater, a.id, b.id)}; }
inline Mask operator&(Mask a, Mask b) { return {Trace(Op::kAnd, a.id, b.id)}; }
inline Int IfThenElseZero(Mask condition, Int value) { return {Trace(Op::kAnd, condition.id, value.id)}; }
inline Int LiteralInt(std::int32_t value) { return ConstantInt(Float{}, value); }

// -x as the reference engine negates: the sign bit flipped, NaNs included.
inline Float Negate(Float x) {
  return {Trace(Op::kXor, x.id, ConstantInt(x, std::numeric_limits<std::int32_t>::min()).id)};
}

using Vec4F = semantics::Vec4<Float>;

// ---- tracing a program: the reference engine's Execute with Float lanes ------------------------------

// Input and store nodes name a lane and, above kGroupShift, which of the loop's vertex groups
// (a vector of vertices each) they belong to.
constexpr int kGroupShift = 16;
constexpr std::uint32_t kLaneMask = (1u << kGroupShift) - 1;

class Tracer {
 public:
  Tracer(int group, std::span<const UniformInput> uniform_inputs)
      : group_(static_cast<std::uint32_t>(group) << kGroupShift), uniform_inputs_(uniform_inputs) {
    const Float zero = Zero();
    for (auto& temp : temps_) temp.fill(zero);
  }

  void Trace(const Instruction& instruction) {
    switch (instruction.opcode) {
#define VS11_JIT_TRACE_CASE(name, ...) \
  case Opcode::k##name: Execute<semantics::name##Semantics>(instruction); break;
      VS11_OPCODES(VS11_JIT_TRACE_CASE)
#undef VS11_JIT_TRACE_CASE
    }
  }

  // A store of every output lane the program wrote, with its final value.
  void StoreOutputs() {
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      for (int c = 0; c < 4; ++c) {
        if (outputs_[slot][c].id != kNoArg) {
          jit::Trace(Op::kStore, outputs_[slot][c].id, kNoArg, kNoArg,
                     static_cast<std::uint32_t>(batch::OutputLane(slot, c)) | group_);
        }
      }
    }
  }

 private:
  static Float Zero() { return Constant(Float{}, 0.0f); }

  // c[a0.x + index] of every vertex, component by component (the batch engine's GatherKernel):
  // registers outside the bank read row 0 of the constant table, which holds zeros.
  Vec4F Gather(long index) const {
    const Int register_index = address_ + LiteralInt(static_cast<std::int32_t>(index));
    const Int count = {jit::Trace(Op::kConstantCount)};
    const Mask in_range = (register_index > LiteralInt(-1)) & (count > register_index);
    const Int row = IfThenElseZero(in_range, register_index + LiteralInt(batch::kFirstConstantRow));
    const Int offset = ShiftLeft<2>(row);
    Vec4F value;
    for (int c = 0; c < 4; ++c) {
      value[c] = {jit::Trace(Op::kGather, offset.id, kNoArg, kNoArg, static_cast<std::uint32_t>(c))};
    }
    return value;
  }

  // a0.x = AddressFromFloat(x), in the reference engine's order of tests (NaN fails both).
  static Int AddressFrom(Float x) {
    const Float whole = Floor(x);
    const Float limit = Constant(x, static_cast<float>(kAddressLimit));
    const Float below = IfThenElse(whole < limit, whole, limit);
    return ToInt(IfThenElse(whole > Constant(x, -static_cast<float>(kAddressLimit)), below,
                            Constant(x, -static_cast<float>(kAddressLimit))));
  }

  Vec4F ReadRegister(const RegisterRef& reg, int row) const {
    const long index = static_cast<long>(reg.index) + row;
    Vec4F value;
    value.fill(Zero());
    switch (reg.file) {
      case RegisterFile::kConst:
        if (reg.relative && address_written_) return Gather(index);
        if (index < 0) break;  // before any write a0 is 0
        for (int c = 0; c < 4; ++c) {
          value[c] = {jit::Trace(Op::kConstant, kNoArg, kNoArg, kNoArg, batch::ConstantIndex(static_cast<int>(index), c))};
        }
        break;
      case RegisterFile::kTemp:
        if (index < kTempRegisterCount) value = temps_[static_cast<std::size_t>(index)];
        break;
      case RegisterFile::kInput:
        if (index >= kInputRegisterCount) break;
        for (int c = 0; c < 4; ++c) {
          const auto uniform = std::ranges::find_if(uniform_inputs_, [&](const UniformInput& u) {
            return u.reg == index && u.component == c;
          });
          value[c] = uniform != uniform_inputs_.end()
                         ? Constant(Float{}, uniform->value)
                         : Float{jit::Trace(Op::kInput, kNoArg, kNoArg, kNoArg,
                                            static_cast<std::uint32_t>(batch::InputLane(static_cast<int>(index), c)) | group_)};
        }
        break;
      default: break;  // outputs and a0 are not readable
    }
    return value;
  }

  Vec4F Fetch(const SourceOperand& source, int row) const {
    const Vec4F base = ReadRegister(source.reg, row);
    Vec4F value;
    for (int lane = 0; lane < 4; ++lane) {
      const Float v = base[source.swizzle[lane]];
      value[lane] = source.negate ? Negate(v) : v;
    }
    return value;
  }

  void Store(const DestOperand& dest, const Vec4F& value, int lane_count) {
    Vec4F* target = nullptr;
    if (dest.reg.file == RegisterFile::kAddress) {
      if (dest.mask.has(0)) {
        address_ = AddressFrom(value[0]);
        address_written_ = true;
      }
      return;
    }
    if (dest.reg.file == RegisterFile::kTemp) {
      if (dest.reg.index < kTempRegisterCount) target = &temps_[static_cast<std::size_t>(dest.reg.index)];
    } else if (std::optional<int> slot = OutputSlotOf(dest.reg)) {
      target = &outputs_[static_cast<std::size_t>(*slot)];
    }
    if (target == nullptr) return;
    for (int lane = 0; lane < lane_count; ++lane) {
      if (dest.mask.has(lane)) (*target)[lane] = value[lane];
    }
  }

  static Float DotOfWidth(int width, const Vec4F& a, const Vec4F& b) {
    return width == 3 ? semantics::Dot<Float, 3>(a, b) : semantics::Dot<Float, 4>(a, b);
  }

  template <class Semantics>
  void Execute(const Instruction& instruction) {
    const OpcodeInfo& info = instruction.info();
    std::array<Vec4F, 3> src{};
    for (int s = 0; s < info.source_count(); ++s) src[s] = Fetch(instruction.sources[s], 0);
    Vec4F result;
    int lane_count = 4;
    if constexpr (requires(Float v) { Semantics::Lane(v, v, v); }) {
      for (int lane = 0; lane < 4; ++lane) result[lane] = Semantics::Lane(src[0][lane], src[1][lane], src[2][lane]);
    } else if constexpr (requires(Float v) { Semantics::Scalar(v); }) {
      result.fill(Semantics::Scalar(src[0][3]));
    } else if constexpr (requires(Vec4F v) { Semantics::Vector(v, v); }) {
      result = Semantics::Vector(src[0], src[1]);
    } else if (info.kind == ResultKind::kDotProduct) {
      result.fill(DotOfWidth(info.dot_width, src[0], src[1]));
    } else if (info.kind == ResultKind::kMatrix) {
      for (int row = 0; row < info.matrix_rows; ++row) {
        result[row] = DotOfWidth(info.dot_width, src[0], Fetch(instruction.sources[1], row));
      }
      lane_count = info.matrix_rows;
    } else {
      return;  // nop, dcl, def
    }
    Store(instruction.dest, result, lane_count);
  }

  std::array<Vec4F, kTempRegisterCount> temps_{};
  std::array<Vec4F, kOutputSlotCount> outputs_{};
  Int address_;
  bool address_written_ = false;
  std::uint32_t group_;
  std::span<const UniformInput> uniform_inputs_;
};

// ---- register allocation and code --------------------------------------------------------------------

// The one thing that differs between the instruction sets: how wide a vector is and how many there are.
// The graph, the allocator and the schedule are the same; Emitter picks the encodings.
struct VectorShape {
  JitIsa isa;
  int lanes;      // floats per vector register
  int registers;  // vector registers
  int bytes() const { return 4 * lanes; }
};
constexpr VectorShape kAvx2Shape{JitIsa::kAvx2, 8, 16};
constexpr VectorShape kAvx512Shape{JitIsa::kAvx512, 16, 32};
constexpr int kMaxVectorRegisters = 32;

bool Rematerializable(Op op) {
  return op == Op::kInput || op == Op::kConstant || op == Op::kLiteral || op == Op::kConstantCount;
}

class Emitter : public Xbyak::CodeGenerator {
 public:
  // `hoisted`: how many of the most used constants are loaded into registers once, before the loop,
  // leaving the others to the values computed in it.
  // `trial_buffer`: generate into this buffer (code_size bytes), only to count operations, instead
  // of into executable pages.
  Emitter(const std::vector<Node>& nodes, VectorShape shape, int groups, std::size_t code_size, int hoisted,
          std::uint8_t* trial_buffer = nullptr)
      // Written, then made read+execute (never writable and executable at once).
      : Xbyak::CodeGenerator(code_size, trial_buffer != nullptr ? trial_buffer : Xbyak::DontSetProtectRWE),
        nodes_(nodes),
        shape_(shape),
        wide_(shape.isa == JitIsa::kAvx512),
        groups_(groups),
        trial_(trial_buffer != nullptr),
        spill_slot_(nodes.size(), -1),
        hoisted_(static_cast<std::size_t>(hoisted)) {}

  // Emits the whole function; the literal pool and the spill size are known afterwards.
  void Generate() {
    const Registers& r = regs_;
    FindUses();
    const std::vector<int> pointer_lanes = KeepLanePointers();
    for (std::size_t k = 0; k < pointer_lanes.size(); ++k) push(kLanePointerRegisters[k]);
    mov(r.read_lanes, ptr[r.arguments + offsetof(RunArguments, read_lanes)]);
    mov(r.write_lanes, ptr[r.arguments + offsetof(RunArguments, write_lanes)]);
    mov(r.constants, ptr[r.arguments + offsetof(RunArguments, constants)]);
    mov(r.end, ptr[r.arguments + offsetof(RunArguments, count)]);
    shl(r.end, 2);
    mov(r.literals, ptr[r.arguments + offsetof(RunArguments, literals)]);
    mov(r.spill, ptr[r.arguments + offsetof(RunArguments, spill)]);
    for (std::size_t k = 0; k < pointer_lanes.size(); ++k) {
      const int lane = pointer_lanes[k];
      mov(kLanePointerRegisters[k], ptr[(IsStoreLane(lane) ? r.write_lanes : r.read_lanes) + 8 * LaneIndex(lane)]);
    }
    HoistConstants();
    loop_memory_operations_ = 0;  // the body's from here
    xor_(r.offset, r.offset);
    Xbyak::Label loop;
    L(loop);
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (live_[n]) Emit(static_cast<int>(n));
    }
    add(r.offset, shape_.bytes() * groups_);
    cmp(r.offset, r.end);
    jb(loop, T_NEAR);
    vzeroupper();
    for (std::size_t k = pointer_lanes.size(); k-- > 0;) pop(kLanePointerRegisters[k]);
    ret();
    if (!trial_) setProtectModeRE();
  }

  const std::vector<float>& literals() const { return literals_; }
  int spill_slots() const { return spill_slots_; }
  VectorShape shape() const { return shape_; }
  int groups() const { return groups_; }
  int spilled_values() const { return spilled_values_; }
  std::size_t hoisted() const { return hoisted_; }  // after Generate: at most the constants there are
  // Loads and stores in the loop body: what the number of hoisted constants is chosen by.
  int loop_memory_operations() const { return loop_memory_operations_; }

 private:
  // Lane keys: loads and stores go through different tables, so a stored lane is told apart.
  static constexpr int kStoreLaneFlag = 1 << 16;
  static bool IsStoreLane(int key) { return (key & kStoreLaneFlag) != 0; }
  static int LaneIndex(int key) { return key & (kStoreLaneFlag - 1); }
  static int LaneKey(const Node& node) {
    return static_cast<int>(node.immediate & kLaneMask) | (node.op == Op::kStore ? kStoreLaneFlag : 0);
  }
  // Callee-saved registers (pushed and popped), each holding one lane's address for the whole call.
  inline static const std::array<Xbyak::Reg64, 6> kLanePointerRegisters = {
      Xbyak::Reg64(Xbyak::Operand::RBX), Xbyak::Reg64(Xbyak::Operand::RBP), Xbyak::Reg64(Xbyak::Operand::R12),
      Xbyak::Reg64(Xbyak::Operand::R13), Xbyak::Reg64(Xbyak::Operand::R14), Xbyak::Reg64(Xbyak::Operand::R15)};

  // Chooses the lanes whose addresses live in registers (the most used ones); returns their keys.
  std::vector<int> KeepLanePointers() {
    std::map<int, int> uses;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const Node& node = nodes_[n];
      if (!live_[n] || (node.op != Op::kInput && node.op != Op::kStore)) continue;
      uses[LaneKey(node)] += std::max<int>(1, static_cast<int>(uses_[n].size()));
    }
    std::vector<std::pair<int, int>> by_use;
    for (const auto& [key, count] : uses) by_use.emplace_back(count, key);
    std::stable_sort(by_use.begin(), by_use.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<int> keys;
    for (const auto& [count, key] : by_use) {
      if (keys.size() == kLanePointerRegisters.size()) break;
      lane_pointer_[key] = kLanePointerRegisters[keys.size()];
      keys.push_back(key);
    }
    return keys;
  }

  // The address of this vertex group in a lane, loading the lane's address into `lane` if needed.
  Xbyak::RegExp LaneAddress(const Node& node) {
    const int group_offset = shape_.bytes() * static_cast<int>(node.immediate >> kGroupShift);
    const auto it = lane_pointer_.find(LaneKey(node));
    if (it != lane_pointer_.end()) return it->second + regs_.offset + group_offset;
    ++loop_memory_operations_;
    mov(regs_.lane, ptr[(node.op == Op::kStore ? regs_.write_lanes : regs_.read_lanes) + 8 * (node.immediate & kLaneMask)]);
    return regs_.lane + regs_.offset + group_offset;
  }

  // Loads the most used constants into the top registers before the loop, for good.
  void HoistConstants() {
    std::vector<std::pair<int, int>> by_use;  // (uses, node)
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const Op op = nodes_[n].op;
      if (live_[n] && op != Op::kInput && Rematerializable(op)) by_use.emplace_back(uses_[n].size(), n);
    }
    std::stable_sort(by_use.begin(), by_use.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    hoisted_ = std::min(hoisted_, by_use.size());
    available_registers_ = shape_.registers - static_cast<int>(hoisted_);
    for (std::size_t k = 0; k < hoisted_; ++k) {
      const int value = by_use[k].second;
      Materialize(value, shape_.registers - 1 - static_cast<int>(k));
      pinned_values_.push_back(value);
    }
  }
  bool Hoisted(int value) const {
    return std::find(pinned_values_.begin(), pinned_values_.end(), value) != pinned_values_.end();
  }

  void FindUses() {
    live_.assign(nodes_.size(), false);
    uses_.assign(nodes_.size(), {});
    for (std::size_t n = nodes_.size(); n-- > 0;) {
      if (nodes_[n].op == Op::kStore) live_[n] = true;
      if (!live_[n]) continue;
      for (int arg : nodes_[n].args) {
        if (arg != kNoArg) live_[static_cast<std::size_t>(arg)] = true;
      }
    }
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (!live_[n]) continue;
      for (int arg : nodes_[n].args) {
        if (arg != kNoArg) uses_[static_cast<std::size_t>(arg)].push_back(static_cast<int>(n));
      }
    }
    register_value_.fill(kNoArg);
    where_.assign(nodes_.size(), kNoArg);
  }

  // The position of the next use of `value` after `position`, or "never".
  int NextUse(int value, int position) const {
    const std::vector<int>& uses = uses_[static_cast<std::size_t>(value)];
    const auto it = std::upper_bound(uses.begin(), uses.end(), position);
    return it == uses.end() ? std::numeric_limits<int>::max() : *it;
  }

  // A free register, evicting the value used farthest in the future (not one of `pinned`).
  int TakeRegister(int position, const std::array<int, 3>& pinned) {
    for (int reg = 0; reg < available_registers_; ++reg) {
      if (register_value_[reg] == kNoArg) return reg;
    }
    int victim = -1, farthest = -1;
    for (int reg = 0; reg < available_registers_; ++reg) {
      const int value = register_value_[reg];
      if (std::find(pinned.begin(), pinned.end(), value) != pinned.end()) continue;
      const int next = NextUse(value, position);
      if (next > farthest) farthest = next, victim = reg;
    }
    const int value = register_value_[victim];
    if (!Rematerializable(nodes_[static_cast<std::size_t>(value)].op) && spill_slot_[value] < 0) {
      spill_slot_[value] = spill_slots_++;
      ++spilled_values_;
      ++loop_memory_operations_;
      vmovups(ptr[regs_.spill + shape_.bytes() * spill_slot_[value]], V(victim));
    }
    where_[value] = kNoArg;
    register_value_[victim] = kNoArg;
    return victim;
  }

  // Loads a rematerializable or spilled value into `reg`.
  void Materialize(int value, int reg) {
    const Node& node = nodes_[static_cast<std::size_t>(value)];
    const Xbyak::Xmm vector = V(reg);
    ++loop_memory_operations_;
    switch (node.op) {
      case Op::kInput: vmovups(vector, ptr[LaneAddress(node)]); break;
      case Op::kConstant: vbroadcastss(vector, ptr[regs_.constants + 4 * node.immediate]); break;
      case Op::kLiteral: vbroadcastss(vector, ptr[regs_.literals + 4 * LiteralIndex(node.immediate)]); break;
      case Op::kConstantCount: vpbroadcastd(vector, ptr[regs_.arguments + offsetof(RunArguments, constant_count)]); break;
      default: vmovups(vector, ptr[regs_.spill + shape_.bytes() * spill_slot_[value]]); break;
    }
    where_[value] = reg;
    register_value_[reg] = value;
  }

  int LiteralIndex(std::uint32_t bits) {
    const auto it = literal_index_.find(bits);
    if (it != literal_index_.end()) return it->second;
    literals_.push_back(std::bit_cast<float>(bits));
    return literal_index_[bits] = static_cast<int>(literals_.size()) - 1;
  }

  void Emit(int n) {
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    if (Rematerializable(node.op)) return;  // loaded where it is used
    // Operands into registers.
    std::array<Xbyak::Xmm, 3> in = {V(0), V(0), V(0)};
    for (int a = 0; a < 3; ++a) {
      const int arg = node.args[a];
      if (arg == kNoArg) continue;
      if (where_[arg] == kNoArg) Materialize(arg, TakeRegister(n, node.args));
      in[a] = V(where_[arg]);
    }
    if (node.op == Op::kGather) {
      EmitGather(n, in[0]);
      return;
    }
    // Operands used for the last time give their registers up before the result takes one.
    for (int arg : node.args) {
      if (arg != kNoArg && where_[arg] != kNoArg && !Hoisted(arg) && NextUse(arg, n) == std::numeric_limits<int>::max()) {
        register_value_[where_[arg]] = kNoArg;
        where_[arg] = kNoArg;
      }
    }
    if (node.op == Op::kStore) {
      ++loop_memory_operations_;
      vmovups(ptr[LaneAddress(node)], in[0]);
      return;
    }
    if (uses_[static_cast<std::size_t>(n)].empty()) return;
    const int reg = TakeRegister(n, {kNoArg, kNoArg, kNoArg});
    where_[n] = reg;
    register_value_[reg] = n;
    EmitOperation(node, V(reg), in);
  }

  // The operation itself. AVX-512 compares into a mask register, which is then widened to the
  // all-ones lanes the graph's masks are (selects narrow it back), and has no VEX-only forms
  // (vroundps, vblendvps, vpand): the EVEX equivalents compute the same bits.
  void EmitOperation(const Node& node, const Xbyak::Xmm& out, const std::array<Xbyak::Xmm, 3>& in) {
    const auto compare = [&](std::uint8_t predicate) {
      if (wide_) {
        vcmpps(k1, in[0], in[1], predicate);
        vpmovm2d(out, k1);
      } else {
        vcmpps(out, in[0], in[1], predicate);
      }
    };
    switch (node.op) {
      case Op::kAdd: vaddps(out, in[0], in[1]); break;
      case Op::kSub: vsubps(out, in[0], in[1]); break;
      case Op::kMul: vmulps(out, in[0], in[1]); break;
      case Op::kDiv: vdivps(out, in[0], in[1]); break;
      // Toward -inf, no precision exception.
      case Op::kFloor: wide_ ? vrndscaleps(out, in[0], 0x09) : vroundps(out, in[0], 0x09); break;
      case Op::kSqrt: vsqrtps(out, in[0]); break;
      // Ordered predicates: false when either side is NaN, as the C++ comparisons.
      case Op::kLess: compare(0x11); break;          // LT_OQ
      case Op::kGreater: compare(0x1E); break;       // GT_OQ
      case Op::kGreaterEqual: compare(0x1D); break;  // GE_OQ
      case Op::kEqual: compare(0x00); break;         // EQ_OQ
      case Op::kUnordered: compare(0x03); break;     // UNORD_Q
      case Op::kSelect:  // mask ? yes : no
        if (wide_) {
          vpmovd2m(k1, in[0]);
          vblendmps(out | k1, in[2], in[1]);
        } else {
          vblendvps(out, in[2], in[1], in[0]);
        }
        break;
      case Op::kIntAdd: vpaddd(out, in[0], in[1]); break;
      case Op::kIntSub: vpsubd(out, in[0], in[1]); break;
      case Op::kAnd: wide_ ? vpandd(out, in[0], in[1]) : vpand(out, in[0], in[1]); break;
      case Op::kOr: wide_ ? vpord(out, in[0], in[1]) : vpor(out, in[0], in[1]); break;
      case Op::kXor: wide_ ? vpxord(out, in[0], in[1]) : vpxor(out, in[0], in[1]); break;
      case Op::kShiftLeft: vpslld(out, in[0], static_cast<std::uint8_t>(node.immediate)); break;
      case Op::kShiftRight: vpsrad(out, in[0], static_cast<std::uint8_t>(node.immediate)); break;
      case Op::kToInt: vcvttps2dq(out, in[0]); break;
      case Op::kToFloat: vcvtdq2ps(out, in[0]); break;
      case Op::kIntGreater:
        if (wide_) {
          vpcmpgtd(k1, in[0], in[1]);
          vpmovm2d(out, k1);
        } else {
          vpcmpgtd(out, in[0], in[1]);
        }
        break;
      case Op::kInput: case Op::kConstant: case Op::kLiteral: case Op::kConstantCount: case Op::kGather:
      case Op::kStore: break;  // handled by Emit
    }
  }

  // vgatherdps wants its result and index in different registers and clears its mask (with AVX2 a
  // third vector register, with AVX-512 k1), so the result and the mask are taken while the index
  // still holds its register.
  void EmitGather(int n, const Xbyak::Xmm& index) {
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    const int index_value = node.args[0];
    const int reg = TakeRegister(n, node.args);
    where_[n] = reg;
    register_value_[reg] = n;
    const Xbyak::Address address = ptr[regs_.constants + index * 4 + 4 * static_cast<int>(node.immediate)];
    if (wide_) {
      kxnorw(k1, k1, k1);
      vgatherdps(V(reg) | k1, address);
    } else {
      const Xbyak::Xmm mask = V(TakeRegister(n, {index_value, n, kNoArg}));
      vpcmpeqd(mask, mask, mask);
      vgatherdps(V(reg), address, mask);
    }
    ++loop_memory_operations_;
    if (!Hoisted(index_value) && NextUse(index_value, n) == std::numeric_limits<int>::max()) {
      register_value_[where_[index_value]] = kNoArg;
      where_[index_value] = kNoArg;
    }
    if (uses_[static_cast<std::size_t>(n)].empty()) {
      register_value_[reg] = kNoArg;
      where_[n] = kNoArg;
    }
  }

  // rdi: the RunArguments (System V's first argument); the others hold its fields, all scratch
  // registers of the ABI. `offset` walks the batch in bytes up to `end`; `lane` holds a lane's address.
  struct Registers {
    Xbyak::Reg64 arguments, read_lanes, write_lanes, constants, literals, spill, offset, end, lane;
  };
  // Vector register `reg` at the shape's width.
  Xbyak::Xmm V(int reg) const { return wide_ ? Xbyak::Xmm(Xbyak::Zmm(reg)) : Xbyak::Xmm(Xbyak::Ymm(reg)); }

  const std::vector<Node>& nodes_;
  const VectorShape shape_;
  const bool wide_;   // AVX-512
  const int groups_;  // vertex groups (a vector each) per iteration
  const bool trial_;
  const Registers regs_{rdi, rsi, rdx, rcx, r8, r9, r10, r11, rax};
  std::vector<bool> live_;
  std::vector<std::vector<int>> uses_;
  std::vector<int> where_;  // register of each value, kNoArg when not in one
  std::array<int, kMaxVectorRegisters> register_value_{};
  std::vector<int> spill_slot_;
  int spill_slots_ = 0;
  int spilled_values_ = 0;
  std::vector<float> literals_;
  std::map<std::uint32_t, int> literal_index_;
  std::size_t hoisted_;
  int available_registers_ = 0;  // the shape's registers less the hoisted constants
  std::vector<int> pinned_values_;
  std::map<int, Xbyak::Reg64> lane_pointer_;  // by lane key
  int loop_memory_operations_ = 0;
};

class AvxProgram final : public CompiledProgram {
 public:
  using Function = void (*)(const RunArguments*);

  explicit AvxProgram(std::unique_ptr<Emitter> emitter)
      : emitter_(std::move(emitter)),
        function_(emitter_->getCode<Function>()),
        literals_(emitter_->literals()),
        spill_floats_(static_cast<std::size_t>(emitter_->spill_slots()) * static_cast<std::size_t>(emitter_->shape().lanes)) {}

  void Run(RunArguments arguments) const override {
    arguments.literals = literals_.data();
    function_(&arguments);
  }
  std::size_t spill_floats() const override { return spill_floats_; }
  std::span<const std::uint8_t> code() const override { return {emitter_->getCode(), emitter_->getSize()}; }
  int spilled_values() const override { return emitter_->spilled_values(); }
  JitIsa isa() const override { return emitter_->shape().isa; }
  int vertices_per_iteration() const override { return emitter_->shape().lanes * emitter_->groups(); }

 private:
  std::unique_ptr<Emitter> emitter_;
  Function function_;
  std::vector<float> literals_;
  std::size_t spill_floats_;
};

// Bytes of code per traced node, generously: an operation is one or two instructions, a reload or
// spill adds one or two more (each at most 11 bytes).
constexpr std::size_t kCodeBytesPerNode = 48;
constexpr std::size_t kCodeBytesFixed = 512;
// Vector registers always left to the loop's values (the others may hold constants for good).
constexpr int kMinLoopRegisters = 4;
// A program whose longest chain of dependent operations is at least this long (exp, log and lit's
// series) runs several vertex groups per iteration, interleaved instruction by instruction, so that
// the CPU has independent work while a chain waits on its latencies.
constexpr int kLongChain = 24;

Graph TraceProgram(const Program& program, int groups, std::span<const UniformInput> uniform_inputs) {
  Graph graph;
  tracing = &graph;
  std::vector<Tracer> tracers;
  for (int group = 0; group < groups; ++group) tracers.emplace_back(group, uniform_inputs);
  for (const Instruction& instruction : program.instructions) {
    for (Tracer& tracer : tracers) tracer.Trace(instruction);
  }
  for (Tracer& tracer : tracers) tracer.StoreOutputs();
  tracing = nullptr;
  return graph;
}

// Operations on the longest dependency chain.
int LongestChain(const Graph& graph) {
  std::vector<int> depth(graph.nodes().size(), 0);
  int longest = 0;
  for (std::size_t n = 0; n < graph.nodes().size(); ++n) {
    for (int arg : graph.nodes()[n].args) {
      if (arg != kNoArg) depth[n] = std::max(depth[n], depth[static_cast<std::size_t>(arg)] + 1);
    }
    longest = std::max(longest, depth[n]);
  }
  return longest;
}

}  // namespace

std::vector<JitIsa> SupportedIsas() {
  static const std::vector<JitIsa> supported = [] {
    const Xbyak::util::Cpu cpu;
    std::vector<JitIsa> isas;
    if (!cpu.has(Xbyak::util::Cpu::tAVX2)) return isas;
    isas.push_back(JitIsa::kAvx2);
    // vpmovm2d/vpmovd2m (mask lanes to vectors and back) are AVX512DQ.
    if (cpu.has(Xbyak::util::Cpu::tAVX512F) && cpu.has(Xbyak::util::Cpu::tAVX512DQ)) isas.push_back(JitIsa::kAvx512);
    return isas;
  }();
  return supported;
}

std::string_view IsaName(JitIsa isa) {
  switch (isa) {
    case JitIsa::kBest: return "best";
    case JitIsa::kAvx2: return "avx2";
    case JitIsa::kAvx512: return "avx512";
  }
  return "best";
}

std::unique_ptr<CompiledProgram> Compile(const Program& program, std::string& why_not, JitIsa isa,
                                         std::span<const UniformInput> uniform_inputs) {
  const std::vector<JitIsa> supported = SupportedIsas();
  if (supported.empty()) {
    why_not = "the CPU has no AVX2";
    return nullptr;
  }
  if (isa == JitIsa::kBest) isa = supported.back();
  if (std::ranges::find(supported, isa) == supported.end()) {
    why_not = isa == JitIsa::kAvx512 ? "the CPU has no AVX-512 (F and DQ)" : "the CPU lacks the instruction set";
    return nullptr;
  }
  const VectorShape shape = isa == JitIsa::kAvx512 ? kAvx512Shape : kAvx2Shape;
  Graph graph = TraceProgram(program, 1, uniform_inputs);
  int groups = 1;
  // Two groups, with AVX2 or AVX-512: four groups of 16 spilled more than they hid (measured on
  // all_instructions, 1.6 vs 2.8 ms per 65536 vertices), and one group of 16 was slower still.
  if (LongestChain(graph) >= kLongChain) {
    groups = 2;
    graph = TraceProgram(program, groups, uniform_inputs);
  }
  static_assert(batch::kVertexGranule % 64 == 0, "an iteration takes at most 64 vertices");
  try {
    // Each constant kept in a register saves a load per iteration but takes a register from the
    // loop's values, which may then be reloaded or spilled more: the count with the fewest loads
    // and stores in the loop wins (code generation takes microseconds).
    const std::size_t code_size = kCodeBytesFixed + kCodeBytesPerNode * graph.nodes().size();
    std::vector<std::uint8_t> trial_buffer(code_size);
    int best_hoisted = 0, fewest = std::numeric_limits<int>::max();
    for (int hoisted = 0; hoisted <= shape.registers - kMinLoopRegisters && hoisted <= best_hoisted + 2; ++hoisted) {
      Emitter trial(graph.nodes(), shape, groups, code_size, hoisted, trial_buffer.data());
      trial.Generate();
      if (trial.loop_memory_operations() < fewest) fewest = trial.loop_memory_operations(), best_hoisted = hoisted;
      if (trial.hoisted() < static_cast<std::size_t>(hoisted)) break;  // no constants left to keep
    }
    auto emitter = std::make_unique<Emitter>(graph.nodes(), shape, groups, code_size, best_hoisted);
    emitter->Generate();
    return std::make_unique<AvxProgram>(std::move(emitter));
  } catch (const Xbyak::Error& error) {
    why_not = std::string("code generation failed: ") + error.what();
    return nullptr;
  }
}

}  // namespace vs11::jit
