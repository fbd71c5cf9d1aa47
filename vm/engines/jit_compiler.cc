#include "vm/engines/jit_compiler.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <tuple>

#include <xbyak/xbyak.h>
#include <xbyak/xbyak_util.h>

#include "vm/core/machine.h"
#include "vm/engines/batch_plan.h"
#include "vm/engines/jit_graph.h"
#include "vm/engines/register_allocator.h"
#include "vm/ir/graph.h"

namespace vs11::jit {
namespace {

using ir::Node;
using ir::Op;
constexpr int kNoArg = ir::kNoNode;

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
// Vector registers always left to the loop's values (the others may hold constants for good).
constexpr int kMinLoopRegisters = 4;
class Emitter : public Xbyak::CodeGenerator {
 public:
  // `hoisted`: how many of the most used constants are loaded into registers once, before the loop,
  // leaving the others to the values computed in it.
  // The code is generated into `buffer`, plain memory: an Emitter lives only while Compile runs (it
  // refers to Compile's graph), and ExecutableCode copies the code a compiled program keeps.
  Emitter(const ir::Graph& graph, VectorShape shape, int groups, int hoisted, std::span<std::uint8_t> buffer)
      : Xbyak::CodeGenerator(buffer.size(), buffer.data()),
        nodes_(graph.nodes()),
        shape_(shape),
        wide_(shape.isa == JitIsa::kAvx512),
        groups_(groups),
        allocator_(graph, kMaskRegisterEnd),
        hoisted_(static_cast<std::size_t>(hoisted)) {
    assert(hoisted >= 0 && hoisted <= shape.registers - kMinLoopRegisters);
  }

  // Emits the whole function; the literal pool and the spill size are known afterwards.
  // `streaming_stores`: outputs are stored around the caches (vmovntps; every output lane aligned
  // to a vector), for calls whose outputs do not fit in them.
  void Generate(bool streaming_stores = false) {
    streaming_stores_ = streaming_stores;
    const Registers& r = regs_;
    const std::vector<int> pointer_lanes = KeepLanePointers();
    for (std::size_t k = 0; k < pointer_lanes.size(); ++k) push(kLanePointerRegisters[k]);
    mov(r.read_lanes, ptr[r.arguments + offsetof(RunArguments, read_lanes)]);
    mov(r.write_lanes, ptr[r.arguments + offsetof(RunArguments, write_lanes)]);
    mov(r.constants, ptr[r.arguments + offsetof(RunArguments, constants)]);
    // Whole iterations only, none when count is below one: CompiledProgram::Run computes the last
    // count % vertices_per_iteration() vertices on padded copies.
    mov(r.end, ptr[r.arguments + offsetof(RunArguments, count)]);
    and_(r.end, -vertices_per_iteration());
    shl(r.end, 2);
    mov(r.literals, ptr[r.arguments + offsetof(RunArguments, literals)]);
    mov(r.spill, ptr[r.arguments + offsetof(RunArguments, spill)]);
    for (std::size_t k = 0; k < pointer_lanes.size(); ++k) {
      const int lane = pointer_lanes[k];
      mov(kLanePointerRegisters[k], ptr[(IsStoreLane(lane) ? r.write_lanes : r.read_lanes) + 8 * LaneIndex(lane)]);
    }
    HoistConstants();
    if (!wide_) StoreConstantVectors();
    loop_memory_operations_ = 0;  // the body's from here
    xor_(r.offset, r.offset);
    Xbyak::Label loop, done;
    test(r.end, r.end);  // the body runs before the count is compared
    jz(done, T_NEAR);
    L(loop);
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (allocator_.live(static_cast<int>(n))) Emit(static_cast<int>(n));
    }
    add(r.offset, shape_.bytes() * groups_);
    cmp(r.offset, r.end);
    jb(loop, T_NEAR);
    L(done);
    if (streaming_stores_) sfence();  // ordered before whatever tells another thread we are done
    vzeroupper();
    for (std::size_t k = pointer_lanes.size(); k-- > 0;) pop(kLanePointerRegisters[k]);
    ret();
  }

  const std::vector<float>& literals() const { return literals_; }
  int spill_slots() const { return allocator_.spill_slots(); }
  VectorShape shape() const { return shape_; }
  // A power of two (8 or 16 lanes, one or two groups): the loop rounds the count down with a mask.
  int vertices_per_iteration() const { return shape_.lanes * groups_; }
  // The lane table entries the code loads from and stores to (sorted lane indices), after Generate.
  std::vector<int> LoadedLanes() const { return LanesOf(Op::kInput); }
  std::vector<int> StoredLanes() const { return LanesOf(Op::kStore); }
  int spilled_values() const { return allocator_.spilled_values(); }
  int spilled_masks() const { return allocator_.spilled_masks(); }
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

  std::vector<int> LanesOf(Op op) const {
    std::vector<int> lanes;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      if (allocator_.live(static_cast<int>(n)) && nodes_[n].op == op) lanes.push_back(LaneIndex(LaneKey(nodes_[n])));
    }
    std::ranges::sort(lanes);
    lanes.erase(std::unique(lanes.begin(), lanes.end()), lanes.end());
    return lanes;
  }

  // Chooses the lanes whose addresses live in registers (the most used ones); returns their keys.
  std::vector<int> KeepLanePointers() {
    std::map<int, int> uses;
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const Node& node = nodes_[n];
      if (!allocator_.live(static_cast<int>(n)) || (node.op != Op::kInput && node.op != Op::kStore)) continue;
      uses[LaneKey(node)] += std::max<int>(1, static_cast<int>(allocator_.users(static_cast<int>(n)).size()));
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
      if (allocator_.live(static_cast<int>(n)) && op != Op::kInput && Rematerializable(op)) {
        by_use.emplace_back(allocator_.users(static_cast<int>(n)).size(), n);
      }
    }
    std::stable_sort(by_use.begin(), by_use.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    hoisted_ = std::min(hoisted_, by_use.size());
    available_registers_ = shape_.registers - static_cast<int>(hoisted_);
    for (std::size_t k = 0; k < hoisted_; ++k) {
      const int value = by_use[k].second;
      Materialize(value, shape_.registers - 1 - static_cast<int>(k));
      allocator_.Hoist(value);
    }
  }
  // AVX2 has no broadcast operands: before the loop, every constant not kept in a register is
  // stored once as a whole vector in a slot of the spill buffer, which operations then read as a
  // memory operand (MemoryOperand) instead of broadcasting it into a register at each iteration.
  void StoreConstantVectors() {
    const Xbyak::Xmm scratch = V(0);  // holds no value yet; the hoisted constants sit at the top
    for (std::size_t n = 0; n < nodes_.size(); ++n) {
      const int value = static_cast<int>(n);
      if (!allocator_.live(value) || nodes_[n].op != Op::kConstant || allocator_.Hoisted(value)) continue;
      vbroadcastss(scratch, ptr[regs_.constants + 4 * nodes_[n].immediate]);
      vmovups(SpillSlot(allocator_.NewSpillSlot(value)), scratch);
    }
  }
  Xbyak::Address SpillSlot(int slot) const { return ptr[regs_.spill + shape_.bytes() * slot]; }

  // A free register for `value` (a vector register, or for an AVX-512 mask a mask register), storing
  // the value the allocator evicts for it to its spill slot first.
  int TakeRegister(int value, int position, const PinnedValues& pinned) {
    const bool mask = InMaskRegister(value);
    const RegisterAllocator::Taken taken =
        allocator_.TakeRegister(mask ? kFirstMaskRegister : 0, mask ? kMaskRegisterEnd : available_registers_, position,
                                pinned, mask);
    if (taken.spill) {
      ++loop_memory_operations_;
      const Xbyak::Address slot = SpillSlot(allocator_.spill_slot(*taken.spill));
      mask ? kmovw(slot, K(taken.reg)) : vmovups(slot, V(taken.reg));
    }
    return taken.reg;
  }

  // Loads a rematerializable or spilled value into `reg`.
  void Materialize(int value, int reg) {
    const Node& node = nodes_[static_cast<std::size_t>(value)];
    ++loop_memory_operations_;
    const Xbyak::Address spilled = SpillSlot(allocator_.spill_slot(value));
    switch (node.op) {
      case Op::kInput: vmovups(V(reg), ptr[LaneAddress(node)]); break;
      case Op::kConstant: vbroadcastss(V(reg), ptr[regs_.constants + 4 * node.immediate]); break;
      case Op::kLiteral: vbroadcastss(V(reg), ptr[regs_.literals + 4 * LiteralIndex(node.immediate)]); break;
      case Op::kConstantCount: vpbroadcastd(V(reg), ptr[regs_.arguments + offsetof(RunArguments, constant_count)]); break;
      default: InMaskRegister(value) ? kmovw(K(reg), spilled) : vmovups(V(reg), spilled); break;
    }
    allocator_.Assign(value, reg);
  }

  int LiteralIndex(std::uint32_t bits) {
    const auto it = literal_index_.find(bits);
    if (it != literal_index_.end()) return it->second;
    literals_.push_back(std::bit_cast<float>(bits));
    return literal_index_[bits] = static_cast<int>(literals_.size()) - 1;
  }
  // The literal repeated across a whole vector in the pool (for AVX2, which has no broadcast
  // operands): its first float's index.
  int WideLiteralIndex(std::uint32_t bits) {
    const auto it = wide_literal_index_.find(bits);
    if (it != wide_literal_index_.end()) return it->second;
    const int first = static_cast<int>(literals_.size());
    literals_.insert(literals_.end(), static_cast<std::size_t>(shape_.lanes), std::bit_cast<float>(bits));
    return wide_literal_index_[bits] = first;
  }

  // Which argument of `op` may be a memory operand (the instruction's last source: b of a binary
  // operation or select, the only source of a unary one), or kNoArg.
  static int MemoryArgument(Op op) {
    switch (op) {
      case Op::kAdd: case Op::kSub: case Op::kMul: case Op::kDiv:
      case Op::kLess: case Op::kGreater: case Op::kGreaterEqual: case Op::kEqual: case Op::kUnordered:
      case Op::kIntGreater: case Op::kIntAdd: case Op::kIntSub: case Op::kIntAnd: case Op::kIntOr: case Op::kIntXor:
      case Op::kSelect: case Op::kSelectZero:
        return 1;
      case Op::kFloor: case Op::kSqrt: case Op::kShiftLeft: case Op::kShiftRight: case Op::kToInt: case Op::kToFloat:
        return 0;
      default:
        return kNoArg;
    }
  }

  // Where `value`, which is in no register, can be read by `user`'s instruction straight from memory:
  // a spilled vector, and with AVX-512 a constant or literal broadcast from its float ({1to16}; not
  // for the masked move of a select-zero) or with AVX2 a constant or literal stored as a vector.
  // Such an operand takes no register, which spares the loop's other values. An input lane is
  // loaded into a register instead: read from memory at each of its uses, all_instructions and
  // skinning ran 3-5 % slower.
  std::optional<Xbyak::Address> MemoryOperand(int value, Op user) {
    const Node& node = nodes_[static_cast<std::size_t>(value)];
    switch (node.op) {
      case Op::kInput: return std::nullopt;
      case Op::kConstant:
        if (!wide_) return SpillSlot(allocator_.spill_slot(value));  // StoreConstantVectors
        if (user == Op::kSelectZero) return std::nullopt;
        return ptr_b[regs_.constants + 4 * node.immediate];
      case Op::kLiteral:
        if (!wide_) return ptr[regs_.literals + 4 * WideLiteralIndex(node.immediate)];
        if (user == Op::kSelectZero) return std::nullopt;
        return ptr_b[regs_.literals + 4 * LiteralIndex(node.immediate)];
      case Op::kConstantCount: return std::nullopt;
      default:
        if (allocator_.spill_slot(value) < 0 || InMaskRegister(value)) return std::nullopt;
        return SpillSlot(allocator_.spill_slot(value));
    }
  }

  void Emit(int n) {
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    if (Rematerializable(node.op)) return;  // loaded where it is used
    // Operands into registers, but for one that the instruction can read from memory where it is.
    const int memory_argument = MemoryArgument(node.op);
    std::array<int, 3> in = {0, 0, 0};  // registers
    for (int a = 0; a < 3; ++a) {
      const int arg = node.args[a];
      if (arg == kNoArg || a == memory_argument) continue;
      if (allocator_.where(arg) == kNoArg) Materialize(arg, TakeRegister(arg, n, node.args));
      in[a] = allocator_.where(arg);
    }
    std::optional<Xbyak::Address> memory;
    if (memory_argument != kNoArg) {
      const int arg = node.args[memory_argument];
      if (allocator_.where(arg) == kNoArg) memory = MemoryOperand(arg, node.op);
      if (memory) {
        ++loop_memory_operations_;
      } else {
        if (allocator_.where(arg) == kNoArg) Materialize(arg, TakeRegister(arg, n, node.args));
        in[memory_argument] = allocator_.where(arg);
      }
    }
    if (node.op == Op::kGather) {
      EmitGather(n, V(in[0]));
      return;
    }
    // Operands used for the last time give their registers up before the result takes one.
    for (int arg : node.args) allocator_.ReleaseAfterLastUse(arg, n);
    if (node.op == Op::kStore) {
      ++loop_memory_operations_;
      streaming_stores_ ? vmovntps(ptr[LaneAddress(node)], V(in[0])) : vmovups(ptr[LaneAddress(node)], V(in[0]));
      return;
    }
    if (allocator_.users(n).empty()) return;
    const int reg = TakeRegister(n, n, {kNoArg, kNoArg, kNoArg});
    allocator_.Assign(n, reg);
    EmitOperation(node, reg, in, memory_argument, memory);
  }

  // The operation itself, on registers `in` into `out`. AVX-512 keeps masks in mask registers, which
  // selects use directly, and has no VEX-only forms (vroundps, vblendvps, vpand): the EVEX
  // equivalents compute the same bits.
  // Where `memory` holds an address, argument `memory_argument` is read from it instead of a register.
  void EmitOperation(const Node& node, int out, const std::array<int, 3>& in, int memory_argument,
                     const std::optional<Xbyak::Address>& memory) {
    const Xbyak::Xmm a_register = V(in[0]), b_register = V(in[1]), c = V(in[2]), result = V(out);
    const auto operand = [&](int argument, const Xbyak::Xmm& in_register) -> const Xbyak::Operand& {
      if (memory && memory_argument == argument) return *memory;
      return in_register;
    };
    const Xbyak::Operand& a = operand(0, a_register);
    const Xbyak::Operand& b = operand(1, b_register);
    const auto compare = [&](std::uint8_t predicate) {
      wide_ ? vcmpps(K(out), a_register, b, predicate) : vcmpps(result, a_register, b, predicate);
    };
    switch (node.op) {
      case Op::kAdd: vaddps(result, a_register, b); break;
      case Op::kSub: vsubps(result, a_register, b); break;
      case Op::kMul: vmulps(result, a_register, b); break;
      case Op::kDiv: vdivps(result, a_register, b); break;
      // Toward -inf, no precision exception.
      case Op::kFloor: wide_ ? vrndscaleps(result, a, 0x09) : vroundps(result, a, 0x09); break;
      case Op::kSqrt: vsqrtps(result, a); break;
      // Ordered predicates: false when either side is NaN, as the C++ comparisons.
      case Op::kLess: compare(0x11); break;          // LT_OQ
      case Op::kGreater: compare(0x1E); break;       // GT_OQ
      case Op::kGreaterEqual: compare(0x1D); break;  // GE_OQ
      case Op::kEqual: compare(0x00); break;         // EQ_OQ
      case Op::kUnordered: compare(0x03); break;     // UNORD_Q
      case Op::kIntGreater: wide_ ? vpcmpgtd(K(out), a_register, b) : vpcmpgtd(result, a_register, b); break;
      case Op::kSelect:  // mask ? yes : no
        wide_ ? vblendmps(result | K(in[0]), c, b) : vblendvps(result, c, b, a_register);
        break;
      case Op::kSelectZero: wide_ ? vmovdqa32(result | K(in[0]) | T_z, b) : vpand(result, a_register, b); break;
      case Op::kIntAdd: vpaddd(result, a_register, b); break;
      case Op::kIntSub: vpsubd(result, a_register, b); break;
      case Op::kIntAnd: wide_ ? vpandd(result, a_register, b) : vpand(result, a_register, b); break;
      case Op::kIntOr: wide_ ? vpord(result, a_register, b) : vpor(result, a_register, b); break;
      case Op::kIntXor: wide_ ? vpxord(result, a_register, b) : vpxor(result, a_register, b); break;
      case Op::kShiftLeft: vpslld(result, a, static_cast<std::uint8_t>(node.immediate)); break;
      case Op::kShiftRight: vpsrad(result, a, static_cast<std::uint8_t>(node.immediate)); break;
      case Op::kToInt: vcvttps2dq(result, a); break;
      case Op::kToFloat: vcvtdq2ps(result, a); break;
      case Op::kInput: case Op::kConstant: case Op::kLiteral: case Op::kConstantCount: case Op::kGather:
      case Op::kStore: break;  // handled by Emit
      // Not in the jit's graph: lowered away (ir::LowerToBitOperations; relative rows to gathers, jit_graph.cc).
      case Op::kAbs: case Op::kNegate: case Op::kBitsOf: case Op::kFloatFromBits: case Op::kRelativeRow:
      case Op::kComponent: assert(false && "not lowered"); break;
    }
  }

  // vgatherdps wants its result and index in different registers and clears its mask (with AVX2 a
  // third vector register, with AVX-512 k1), so the result and the mask are taken while the index
  // still holds its register, and before the branch below: both paths leave the registers alike.
  // Where every vertex of the vector reads the same row (a skinned mesh's neighbouring vertices
  // share their bones), one broadcast load replaces the gather's one load per vertex; the gather
  // stays for a vector whose vertices differ. Either way the same float is read for each vertex.
  void EmitGather(int n, const Xbyak::Xmm& index) {
    const Node& node = nodes_[static_cast<std::size_t>(n)];
    const int index_value = node.args[0];
    const int reg = TakeRegister(n, n, node.args);
    allocator_.Assign(n, reg);
    const Xbyak::Xmm result = V(reg), first_lane = Xbyak::Xmm(index.getIdx());
    const Xbyak::Xmm mask = wide_ ? result : V(TakeRegister(n, n, {index_value, n, kNoArg}));
    const int component_bytes = 4 * static_cast<int>(node.immediate);
    const Xbyak::Reg32 row = regs_.lane.cvt32();
    Xbyak::Label divergent, done;
    vpbroadcastd(result, first_lane);
    if (wide_) {
      vpcmpeqd(k1, result, index);
      kortestw(k1, k1);  // carry: every lane equal
      jnc(divergent, T_NEAR);
    } else {
      vpcmpeqd(result, result, index);
      vmovmskps(row, result);
      cmp(row, (1 << shape_.lanes) - 1);
      jne(divergent, T_NEAR);
    }
    vmovd(row, first_lane);  // a float offset, never negative (vm/core/constant_gather.h): rax is zero-extended
    vbroadcastss(result, ptr[regs_.constants + regs_.lane * 4 + component_bytes]);
    jmp(done, T_NEAR);
    L(divergent);
    const Xbyak::Address address = ptr[regs_.constants + index * 4 + component_bytes];
    if (wide_) {
      kxnorw(k1, k1, k1);
      vgatherdps(result | k1, address);
    } else {
      vpcmpeqd(mask, mask, mask);
      vgatherdps(result, address, mask);
    }
    L(done);
    ++loop_memory_operations_;
    allocator_.ReleaseAfterLastUse(index_value, n);
    if (allocator_.users(n).empty()) allocator_.Release(n);
  }

  // rdi: the RunArguments (System V's first argument); the others hold its fields, all scratch
  // registers of the ABI. `offset` walks the batch in bytes up to `end`; `lane` holds a lane's address.
  struct Registers {
    Xbyak::Reg64 arguments, read_lanes, write_lanes, constants, literals, spill, offset, end, lane;
  };
  // Vector register `reg` at the shape's width.
  Xbyak::Xmm V(int reg) const { return wide_ ? Xbyak::Xmm(Xbyak::Zmm(reg)) : Xbyak::Xmm(Xbyak::Ymm(reg)); }
  // Register numbers from kMaskRegisterBase on are AVX-512's mask registers: k2..k7 hold masks (k0
  // cannot mask an operation, k1 is the gathers' scratch).
  static constexpr int kMaskRegisterBase = kMaxVectorRegisters;
  static constexpr int kFirstMaskRegister = kMaskRegisterBase + 2;
  static constexpr int kMaskRegisterEnd = kMaskRegisterBase + 8;
  static Xbyak::Opmask K(int reg) { return Xbyak::Opmask(reg - kMaskRegisterBase); }
  static_assert(kMaskRegisterEnd - kFirstMaskRegister > std::tuple_size_v<PinnedValues>,
                "TakeRegister needs a mask register that holds no pinned value");
  static_assert(kMinLoopRegisters > std::tuple_size_v<PinnedValues>,
                "TakeRegister needs a vector register that holds no pinned value");
  bool InMaskRegister(int value) const { return wide_ && nodes_[static_cast<std::size_t>(value)].type == ir::Type::kMask; }

  const std::vector<Node>& nodes_;
  const VectorShape shape_;
  const bool wide_;   // AVX-512
  const int groups_;  // vertex groups (a vector each) per iteration
  bool streaming_stores_ = false;
  const Registers regs_{rdi, rsi, rdx, rcx, r8, r9, r10, r11, rax};
  RegisterAllocator allocator_;
  std::vector<float> literals_;
  std::map<std::uint32_t, int> literal_index_;
  std::map<std::uint32_t, int> wide_literal_index_;
  std::size_t hoisted_;
  int available_registers_ = 0;  // the shape's registers less the hoisted constants
  std::map<int, Xbyak::Reg64> lane_pointer_;  // by lane key
  int loop_memory_operations_ = 0;
};

// Machine code in pages of its own: written, then made read+execute (never writable and executable
// at once). The code is position independent (its jumps are relative), so it runs where it is copied.
class ExecutableCode {
 public:
  explicit ExecutableCode(std::span<const std::uint8_t> bytes) : pages_(bytes.size(), Xbyak::DontSetProtectRWE) {
    pages_.db(bytes.data(), bytes.size());
    pages_.setProtectModeRE();
  }
  using Function = void (*)(const RunArguments*);
  Function function() const { return pages_.getCode<Function>(); }
  std::span<const std::uint8_t> bytes() const { return {pages_.getCode(), pages_.getSize()}; }

 private:
  Xbyak::CodeArray pages_;
};

// What a compiled program keeps of its emitters: the code, the literal pool, the lanes and the counts.
class AvxProgram final : public CompiledProgram {
 public:
  // The same loop twice: with cached stores and with streaming ones.
  AvxProgram(const Emitter& cached, const Emitter& streaming)
      : cached_(std::span<const std::uint8_t>(cached.getCode(), cached.getSize())),
        streaming_(std::span<const std::uint8_t>(streaming.getCode(), streaming.getSize())),
        literals_(cached.literals()),
        spill_floats_(static_cast<std::size_t>(cached.spill_slots()) * static_cast<std::size_t>(cached.shape().lanes)),
        loaded_lanes_(cached.LoadedLanes()),
        stored_lanes_(cached.StoredLanes()),
        spilled_values_(cached.spilled_values()),
        spilled_masks_(cached.spilled_masks()),
        isa_(cached.shape().isa),
        vertices_per_iteration_(cached.vertices_per_iteration()) {}

  void Run(RunArguments arguments) const override {
    arguments.literals = literals_.data();
    const std::size_t per_iteration = static_cast<std::size_t>(vertices_per_iteration_);
    const std::size_t rest = arguments.count % per_iteration;
    (Streams(arguments) ? streaming_ : cached_).function()(&arguments);  // the whole iterations
    if (rest != 0) RunRest(arguments, arguments.count - rest, rest);
  }
  std::size_t spill_floats() const override { return spill_floats_; }
  std::span<const std::uint8_t> code() const override { return cached_.bytes(); }
  int spilled_values() const override { return spilled_values_; }
  int spilled_masks() const override { return spilled_masks_; }
  JitIsa isa() const override { return isa_; }
  int vertices_per_iteration() const override { return vertices_per_iteration_; }

 private:
  // Large outputs, written a whole cache line of each lane per iteration (every lane aligned to one).
  bool Streams(const RunArguments& arguments) const {
    if (sizeof(float) * static_cast<std::size_t>(vertices_per_iteration_) < kCacheLineBytes) return false;
    if (arguments.count * sizeof(float) * stored_lanes_.size() < kStreamingOutputBytes) return false;
    const auto alignment = static_cast<std::uintptr_t>(kCacheLineBytes);
    return std::ranges::all_of(stored_lanes_, [&](int lane) {
      return reinterpret_cast<std::uintptr_t>(arguments.write_lanes[lane]) % alignment == 0;
    });
  }

  // The last `rest` vertices, fewer than an iteration, from `first` on: one iteration over padded
  // copies of the lanes, of which the first `rest` vertices are copied in and out. (The batch
  // engine never needs this: it passes whole granules of 64 vertices.)
  void RunRest(const RunArguments& arguments, std::size_t first, std::size_t rest) const {
    const std::size_t per_iteration = static_cast<std::size_t>(vertices_per_iteration_);
    std::vector<float> padded((loaded_lanes_.size() + stored_lanes_.size()) * per_iteration, 0.0f);
    // The code reads only input and output entries of the lane table (vm/engines/batch_plan.h).
    std::array<const float*, batch::kArenaLaneBase> read_lanes{};
    std::array<float*, batch::kArenaLaneBase> write_lanes{};
    float* next = padded.data();
    for (const int lane : loaded_lanes_) {
      std::copy_n(arguments.read_lanes[lane] + first, rest, next);
      read_lanes[static_cast<std::size_t>(lane)] = next;
      next += per_iteration;
    }
    for (const int lane : stored_lanes_) {
      write_lanes[static_cast<std::size_t>(lane)] = next;
      next += per_iteration;
    }
    RunArguments padded_arguments = arguments;
    padded_arguments.read_lanes = read_lanes.data();
    padded_arguments.write_lanes = write_lanes.data();
    padded_arguments.count = per_iteration;
    cached_.function()(&padded_arguments);
    for (const int lane : stored_lanes_) {
      std::copy_n(write_lanes[static_cast<std::size_t>(lane)], rest, arguments.write_lanes[lane] + first);
    }
  }

  ExecutableCode cached_, streaming_;
  std::vector<float> literals_;
  std::size_t spill_floats_;
  std::vector<int> loaded_lanes_, stored_lanes_;  // lane table indices
  int spilled_values_, spilled_masks_;
  JitIsa isa_;
  int vertices_per_iteration_;
};

// Bytes of code per recorded node, generously: an operation is one or two instructions, a reload or
// spill adds one or two more (each at most 11 bytes).
constexpr std::size_t kCodeBytesPerNode = 48;
constexpr std::size_t kCodeBytesPerGather = 128;  // the uniformity test, two paths and their jumps
constexpr std::size_t kCodeBytesFixed = 512;
// A program whose longest chain of dependent operations is at least this long (exp, log and lit's
// series) runs several vertex groups per iteration, interleaved instruction by instruction, so that
// the CPU has independent work while a chain waits on its latencies.
constexpr int kLongChain = 24;


}  // namespace

std::vector<JitIsa> SupportedIsas() {
  static const std::vector<JitIsa> supported = [] {
    const Xbyak::util::Cpu cpu;
    std::vector<JitIsa> isas;
    if (!cpu.has(Xbyak::util::Cpu::tAVX2)) return isas;
    isas.push_back(JitIsa::kAvx2);
    // Everything the emitter uses at 512 bits (mask registers as words included) is AVX512F.
    if (cpu.has(Xbyak::util::Cpu::tAVX512F)) isas.push_back(JitIsa::kAvx512);
    return isas;
  }();
  return supported;
}

std::unique_ptr<CompiledProgram> Compile(const Program& program, std::string& why_not, JitIsa isa,
                                         std::span<const UniformInput> uniform_inputs, FloatRules rules) {
  // The IR has no texture read yet: the jit engine runs such a program on the batch kernels.
  if (std::ranges::any_of(program.instructions, [](const Instruction& i) { return i.opcode == Opcode::kTexldl; })) {
    why_not = "texldl (vertex textures) has no machine code yet; the batch kernels run it";
    return nullptr;
  }
  const std::vector<JitIsa> supported = SupportedIsas();
  if (supported.empty()) {
    why_not = "the CPU has no AVX2";
    return nullptr;
  }
  if (isa == JitIsa::kBest) isa = supported.back();
  if (std::ranges::find(supported, isa) == supported.end()) {
    why_not = isa == JitIsa::kAvx512 ? "the CPU has no AVX-512 (F)" : "the CPU lacks the instruction set";
    return nullptr;
  }
  const VectorShape shape = isa == JitIsa::kAvx512 ? kAvx512Shape : kAvx2Shape;
  ir::Graph graph = RecordLoopBody(program, 1, uniform_inputs, rules);
  int groups = 1;
  // Two groups, with AVX2 or AVX-512: four groups of 16 spilled more than they hid (measured on
  // all_instructions, 1.6 vs 2.8 ms per 65536 vertices), and one group of 16 was slower still.
  if (ir::LongestChain(graph) >= kLongChain) {
    groups = 2;
    graph = RecordLoopBody(program, groups, uniform_inputs, rules);
  }
  static_assert(batch::kVertexGranule % 64 == 0, "an iteration takes at most 64 vertices");
  try {
    // Each constant kept in a register saves a load per iteration but takes a register from the
    // loop's values, which may then be reloaded or spilled more: the count with the fewest loads
    // and stores in the loop wins (code generation takes microseconds).
    const auto gathers = static_cast<std::size_t>(
        std::ranges::count_if(graph.nodes(), [](const Node& node) { return node.op == Op::kGather; }));
    const std::size_t code_size =
        kCodeBytesFixed + kCodeBytesPerNode * graph.nodes().size() + kCodeBytesPerGather * gathers;
    std::vector<std::uint8_t> buffer(code_size);
    int best_hoisted = 0, fewest = std::numeric_limits<int>::max();
    for (int hoisted = 0; hoisted <= shape.registers - kMinLoopRegisters && hoisted <= best_hoisted + 2; ++hoisted) {
      Emitter trial(graph, shape, groups, hoisted, buffer);
      trial.Generate();
      if (trial.loop_memory_operations() < fewest) fewest = trial.loop_memory_operations(), best_hoisted = hoisted;
      if (trial.hoisted() < static_cast<std::size_t>(hoisted)) break;  // no constants left to keep
    }
    std::vector<std::uint8_t> streaming_buffer(code_size);
    Emitter cached(graph, shape, groups, best_hoisted, buffer);
    cached.Generate();
    Emitter streaming(graph, shape, groups, best_hoisted, streaming_buffer);
    streaming.Generate(/*streaming_stores=*/true);
    return std::make_unique<AvxProgram>(cached, streaming);
  } catch (const Xbyak::Error& error) {
    why_not = std::string("code generation failed: ") + error.what();
    return nullptr;
  }
}

}  // namespace vs11::jit
