#include "vm/engines/batch_plan.h"

#include <algorithm>
#include <cassert>
#include <cstring>
#include <optional>
#include <span>

#include "vm/core/operands.h"
#include "vm/engines/reference_engine.h"

namespace vs11::batch {

void CopyKernel(const Step& step, const Frame& frame) {
  std::memcpy(frame.write_lanes[step.dest[0]], frame.read_lanes[step.sources[0][0].index],
              frame.count * sizeof(float));
}

// Rare (one step per `mov a0.x`), so it calls the reference engine's conversion rather than a copy
// of it: floor, clamp to +-2^20, NaN to -2^20.
void AddressKernel(const Step& step, const Frame& frame) {
  const float* value = frame.read_lanes[step.sources[0][0].index];
  std::int32_t* address = frame.address + step.address_lane * kBatchSize;
  for (std::size_t i = 0; i < frame.count; ++i) address[i] = AddressFromFloat(value[i]);
}

namespace {

constexpr int kMaxSources = 3;
constexpr int kMaxRows = 4;  // matrix rows, and rows one dot step computes

constexpr Operand ArrayOperand(int lane) { return Operand{static_cast<std::uint32_t>(lane), true}; }
constexpr Operand ZeroOperand() { return Operand{kZeroConstant, false}; }

constexpr OperandKind KindOf(const Operand& operand, bool negate) {
  if (!operand.is_array) return OperandKind::kBroadcast;
  return negate ? OperandKind::kNegatedArray : OperandKind::kArray;
}

// Gives a group of operands that one kernel loads alike a single kind. Only statically-zero operands
// (an unwritten temporary lane, a register past the end of its file) can be broadcasts next to arrays
// in one group: they become reads of the zero lane, which negates to -0 just as a broadcast 0 does.
OperandKind UnifyKind(std::span<Operand* const> operands, bool negate) {
  bool any_array = false, any_broadcast = false;
  for (const Operand* operand : operands) (operand->is_array ? any_array : any_broadcast) = true;
  if (any_array && any_broadcast) {
    for (Operand* operand : operands) {
      if (operand->is_array) continue;
      assert(operand->index == kZeroConstant);
      *operand = ArrayOperand(kZeroLane);
    }
  }
  if (!any_array) return OperandKind::kBroadcast;
  return negate ? OperandKind::kNegatedArray : OperandKind::kArray;
}

Step CopyStep(std::uint16_t from, std::uint16_t to) {
  Step step;
  step.kernel = &CopyKernel;
  step.sources[0][0] = ArrayOperand(from);
  step.dest[0] = to;
  return step;
}

class PlanBuilder {
 public:
  PlanBuilder(const KernelTable& kernels, const Program& program)
      : kernels_(kernels),
        temp_count_(semantics::TempCountOf(program)),
        address_lanes_(semantics::AddressLaneCountOf(program)) {
    for (auto& reg : temp_lanes_) reg.fill(kNoLane);
    for (auto* lanes : {&gather_lanes_, &abs_lanes_}) {
      for (auto& source : *lanes) {
        for (auto& row : source) row.fill(kNoLane);
      }
    }
    address_value_lanes_.fill(kNoLane);
  }

  BatchPlan Build(const Program& program) {
    for (const Instruction& instruction : program.instructions) Compile(instruction);
    for (int lane = 0; lane < 4 * kInputRegisterCount; ++lane) {
      if (inputs_read_[lane]) plan_.input_lanes.push_back(static_cast<std::uint16_t>(InputLane(0, 0) + lane));
    }
    for (int slot = 0; slot < kOutputSlotCount; ++slot) {
      for (int c = 0; c < 4; ++c) {
        if (plan_.stored_lanes[slot] & (1 << c)) plan_.output_lanes.push_back(static_cast<std::uint16_t>(OutputLane(slot, c)));
      }
    }
    return std::move(plan_);
  }

 private:
  std::uint16_t NewArenaLane() { return static_cast<std::uint16_t>(kArenaLaneBase + plan_.arena_lanes++); }
  std::uint16_t TempLane(int reg, int component) {
    std::uint16_t& lane = temp_lanes_[reg][component];
    if (lane == kNoLane) lane = NewArenaLane();
    return lane;
  }
  std::uint16_t ScratchLane(std::uint16_t& lane) {
    if (lane == kNoLane) lane = NewArenaLane();
    return lane;
  }
  // p# of the straight-line form of a later model's flow (vm/core/static_flow.h): 1 or 0 per vertex.
  std::uint16_t PredicateLane(int reg, int component) {
    if (static_cast<std::size_t>(reg) >= predicate_lanes_.size()) {
      predicate_lanes_.resize(static_cast<std::size_t>(reg) + 1, {kNoLane, kNoLane, kNoLane, kNoLane});
    }
    return ScratchLane(predicate_lanes_[static_cast<std::size_t>(reg)][component]);
  }
  bool PredicateWritten(int reg, int component) const {
    return static_cast<std::size_t>(reg) < predicate_written_.size() && predicate_written_[static_cast<std::size_t>(reg)][component];
  }

  // Component `component` of operand `slot` (row `row` of a matrix) with its _abs applied: a step
  // computes |value| into a scratch lane, which the instruction's step then reads (negated if the
  // operand says so: -r0_abs), so that the kernels know only three operand kinds.
  Operand ResolveSource(const SourceOperand& source, int slot, int row, int component) {
    const Operand operand = Resolve(source, slot, row, component);
    if (!source.absolute) return operand;
    const std::uint16_t lane = ScratchLane(abs_lanes_[slot][row][component]);
    if (!(abs_done_[slot][row] & (1 << component))) {
      abs_done_[slot][row] |= static_cast<std::uint8_t>(1 << component);
      Step step;
      step.kernel = kernels_.lane[static_cast<int>(Opcode::kAbs)][0][static_cast<int>(KindOf(operand, false))];
      step.sources[0][0] = operand;
      step.dest[0] = lane;
      abs_steps_.push_back(step);
    }
    return ArrayOperand(lane);
  }

  // Component `component` of register `source.reg` + `row` as the reference engine's ReadRegister
  // sees it at this point of the program. `slot` and `row` name the gather lanes of a relative read.
  Operand Resolve(const SourceOperand& source, int slot, int row, int component) {
    const RegisterRef& reg = source.reg;
    const int index = reg.index + row;
    switch (reg.file) {
      case RegisterFile::kTemp:
        if (index < 0 || index >= temp_count_ || !temp_written_[index][component]) return ZeroOperand();
        return ArrayOperand(TempLane(index, component));
      case RegisterFile::kInput:
        if (index < 0 || index >= kInputRegisterCount) return ZeroOperand();
        inputs_read_[4 * index + component] = true;
        return ArrayOperand(InputLane(index, component));
      case RegisterFile::kConst: {
        const int address_lane = address_lanes_ > 1 ? reg.address.swizzle_bits & 3 : 0;  // vs_1_1: a0.x
        if (reg.relative && address_written_[address_lane]) {
          gathers_[slot][row] |= static_cast<std::uint8_t>(1 << component);
          gather_base_[slot][row] = index;
          gather_address_lane_[slot][row] = static_cast<std::uint8_t>(address_lane);
          return ArrayOperand(ScratchLane(gather_lanes_[slot][row][component]));
        }
        // Before any write to a0 a relative read uses a0 = 0 (VertexState::a0 starts at 0).
        if (index < 0) return ZeroOperand();
        plan_.max_static_constant = std::max(plan_.max_static_constant, index);
        return Operand{ConstantIndex(index, component), false};
      }
      case RegisterFile::kPredicate:  // 0 until written, as p0 starts false
        if (index < 0 || !PredicateWritten(index, component)) return ZeroOperand();
        return ArrayOperand(PredicateLane(index, component));
      default:
        return ZeroOperand();  // outputs and a0 read as 0 (the validator rejects such sources)
    }
  }

  // The lanes an instruction stores, by component (kNoLane where the mask, the opcode, the register
  // file or a matrix's row count leaves the component alone), as vm/core/operands.h's StoreDest.
  std::array<std::uint16_t, 4> DestLanes(const Instruction& instruction) {
    std::array<std::uint16_t, 4> lanes = {kNoLane, kNoLane, kNoLane, kNoLane};
    const RegisterRef& reg = instruction.dest.reg;
    const WriteMask written = semantics::LanesWritten(instruction);
    std::optional<int> slot = OutputSlotOf(reg);
    for (int c = 0; c < 4; ++c) {
      if (!written.has(c)) continue;
      if (reg.file == RegisterFile::kTemp) {
        if (reg.index >= 0 && reg.index < temp_count_) lanes[c] = TempLane(reg.index, c);
      } else if (reg.file == RegisterFile::kAddress) {
        if (c < address_lanes_) lanes[c] = ScratchLane(address_value_lanes_[c]);
      } else if (reg.file == RegisterFile::kPredicate) {
        if (reg.index >= 0) lanes[c] = PredicateLane(reg.index, c);
      } else if (slot) {
        lanes[c] = static_cast<std::uint16_t>(OutputLane(*slot, c));
        plan_.stored_lanes[*slot] |= static_cast<std::uint8_t>(1 << c);
      }
    }
    return lanes;
  }

  // What a predicated write keeps where its predicate does not hold: the lane's value, or 0 for a
  // lane nothing has written yet (p#, a temporary, a0, an output: all start at 0 in a later model).
  std::array<bool, 4> KeptValues(const Instruction& instruction) {
    std::array<bool, 4> kept{};
    const RegisterRef& reg = instruction.dest.reg;
    const std::optional<int> slot = OutputSlotOf(reg);
    for (int c = 0; c < 4; ++c) {
      bool written = false;
      if (reg.file == RegisterFile::kTemp) written = reg.index >= 0 && reg.index < temp_count_ && temp_written_[reg.index][c];
      if (reg.file == RegisterFile::kPredicate) written = PredicateWritten(reg.index, c);
      if (reg.file == RegisterFile::kAddress) written = address_written_[c];
      if (slot) written = (plan_.stored_lanes[*slot] >> c) & 1;
      kept[c] = written;
    }
    return kept;
  }

  // dest[c] = the instruction's predicate lane c ? scratch[c] : old[c], one step for every lane.
  void CompilePredicated(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest,
                         const std::array<bool, 4>& kept) {
    Step step;
    int lanes = 0;
    for (int c = 0; c < 4; ++c) {
      if (dest[c] == kNoLane) continue;
      step.sources[0][lanes] = Resolve(instruction.predicate, 0, 0, instruction.predicate.swizzle[c]);
      step.sources[1][lanes] = ArrayOperand(ScratchLane(predicated_lanes_[c]));
      step.sources[2][lanes] = kept[c] ? ArrayOperand(dest[c]) : ZeroOperand();
      step.dest[lanes++] = dest[c];
    }
    int index = 0;
    for (int s = 0, scale = 1; s < 3; ++s, scale *= kOperandKinds) {
      std::array<Operand*, 4> group;
      for (int l = 0; l < lanes; ++l) group[l] = &step.sources[s][l];
      index += scale * static_cast<int>(UnifyKind(std::span(group.data(), lanes), false));
    }
    step.kernel = kernels_.predicated[instruction.predicate.logical_not ? 1 : 0][lanes - 1][index];
    plan_.steps.push_back(step);
    fusable_dot_ = false;
  }

  void Compile(const Instruction& instruction) {
    const OpcodeInfo& info = instruction.info();
    const bool texldl = instruction.opcode == Opcode::kTexldl;
    if (!info.is_executable() || (info.kind == ResultKind::kNoResult && !texldl)) return;
    const std::array<bool, 4> kept = instruction.predicated ? KeptValues(instruction) : std::array<bool, 4>{};
    const std::array<std::uint16_t, 4> stored = DestLanes(instruction);
    if (std::all_of(stored.begin(), stored.end(), [](std::uint16_t lane) { return lane == kNoLane; })) return;
    // A predicated instruction computes into scratch lanes, then writes through its predicate.
    std::array<std::uint16_t, 4> dest = stored;
    if (instruction.predicated) {
      for (int c = 0; c < 4; ++c) dest[c] = stored[c] == kNoLane ? kNoLane : ScratchLane(predicated_lanes_[c]);
      fusable_dot_ = false;
    }

    gathers_ = {};
    abs_done_ = {};
    steps_.clear();
    abs_steps_.clear();
    switch (info.kind) {
      case ResultKind::kComponentwise: CompileComponentwise(instruction, dest); break;
      case ResultKind::kScalar: CompileScalar(instruction, dest); break;
      case ResultKind::kDotProduct:
      case ResultKind::kMatrix: CompileDot(instruction, dest); break;
      case ResultKind::kVector: CompileVector(instruction, dest); break;
      case ResultKind::kNoResult:
        if (texldl) CompileTexldl(instruction, dest);
        break;
    }
    if (instruction.dest.saturate && !steps_.empty()) AddSaturate(dest);
    if (!steps_.empty()) {
      EmitGathers();
      plan_.steps.insert(plan_.steps.end(), abs_steps_.begin(), abs_steps_.end());
      plan_.steps.insert(plan_.steps.end(), steps_.begin(), steps_.end());
      fusable_dot_ = fusable_candidate_ && abs_steps_.empty();
    }
    fusable_candidate_ = false;
    if (instruction.predicated) CompilePredicated(instruction, stored, kept);

    if (instruction.dest.reg.file == RegisterFile::kAddress) {
      for (int c = 0; c < 4; ++c) {
        if (stored[c] == kNoLane) continue;
        Step step;
        step.kernel = &AddressKernel;
        step.sources[0][0] = ArrayOperand(stored[c]);
        step.address_lane = static_cast<std::uint8_t>(c);
        plan_.steps.push_back(step);
        address_written_[c] = true;
        fusable_dot_ = false;
      }
    }
    if (instruction.dest.reg.file == RegisterFile::kTemp) {
      for (int c = 0; c < 4; ++c) {
        if (stored[c] != kNoLane) temp_written_[instruction.dest.reg.index][c] = true;
      }
    }
    if (instruction.dest.reg.file == RegisterFile::kPredicate) {
      const auto reg = static_cast<std::size_t>(instruction.dest.reg.index);
      if (predicate_written_.size() <= reg) predicate_written_.resize(reg + 1);
      for (int c = 0; c < 4; ++c) predicate_written_[reg][c] = predicate_written_[reg][c] || stored[c] != kNoLane;
    }
  }

  void EmitGathers() {
    for (int slot = 0; slot < kMaxSources; ++slot) {
      for (int row = 0; row < kMaxRows; ++row) {
        if (gathers_[slot][row] == 0) continue;
        Step step;
        step.kernel = kernels_.gather;
        step.base = gather_base_[slot][row];
        step.address_lane = gather_address_lane_[slot][row];
        for (int c = 0; c < 4; ++c) {
          if (gathers_[slot][row] & (1 << c)) step.dest[c] = gather_lanes_[slot][row][c];
        }
        plan_.steps.push_back(step);
        fusable_dot_ = false;
      }
    }
  }

  // _sat: the written lanes clamped in place once the instruction's steps have stored them.
  void AddSaturate(const std::array<std::uint16_t, 4>& dest) {
    Step step;
    int lanes = 0;
    for (std::uint16_t lane : dest) {
      if (lane == kNoLane) continue;
      step.sources[0][lanes] = ArrayOperand(lane);
      step.dest[lanes++] = lane;
    }
    step.kernel = kernels_.saturate[lanes - 1];
    steps_.push_back(step);
    fusable_candidate_ = false;
  }

  // One step for all written lanes; its kernel loads every source of a vertex group before storing,
  // so a destination that is also a source (add r0, r0.yzwx, r0) needs no copy.
  void CompileComponentwise(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest) {
    const int arity = KernelArity(instruction.info());
    Step step;
    int lanes = 0;
    for (int lane = 0; lane < 4; ++lane) {
      if (dest[lane] == kNoLane) continue;
      for (int s = 0; s < arity; ++s) {
        const SourceOperand& source = instruction.sources[s];
        step.sources[s][lanes] = ResolveSource(source, s, 0, source.swizzle[lane]);
      }
      step.dest[lanes++] = dest[lane];
    }
    int index = 0;
    for (int s = 0, scale = 1; s < arity; ++s, scale *= kOperandKinds) {
      std::array<Operand*, 4> group;
      for (int l = 0; l < lanes; ++l) group[l] = &step.sources[s][l];
      step.negate[s] = instruction.sources[s].negate;
      index += scale * static_cast<int>(UnifyKind(std::span(group.data(), lanes), step.negate[s]));
    }
    const auto& kernels = instruction.opcode == Opcode::kSetp ? kernels_.compare[instruction.comparison - 1]
                                                               : kernels_.lane[static_cast<int>(instruction.opcode)];
    step.kernel = kernels[lanes - 1][index];
    steps_.push_back(step);
  }

  // Computes the value once into the first written lane, then copies it to the others.
  void AddReplicas(const std::array<std::uint16_t, 4>& dest) {
    const std::uint16_t first = steps_.back().dest[0];
    for (std::uint16_t lane : dest) {
      if (lane != kNoLane && lane != first) steps_.push_back(CopyStep(first, lane));
    }
  }

  // The caller has checked that `dest` stores at least one lane.
  static std::uint16_t FirstLane(const std::array<std::uint16_t, 4>& dest) {
    for (std::uint16_t lane : dest) {
      if (lane != kNoLane) return lane;
    }
    return kNoLane;
  }

  void CompileScalar(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest) {
    const SourceOperand& source = instruction.sources[0];
    Step step;
    step.sources[0][0] = ResolveSource(source, 0, 0, source.swizzle[3]);  // §3.1: the swizzled w lane
    step.negate[0] = source.negate;
    step.kernel = kernels_.scalar[static_cast<int>(instruction.opcode)]
                                 [static_cast<int>(KindOf(step.sources[0][0], source.negate))];
    step.dest[0] = FirstLane(dest);
    steps_.push_back(step);
    AddReplicas(dest);
  }

  // dp3/dp4 (one row, replicated) and m*x* (a row per written lane) share the dot kernels. A dp that
  // follows another dot step with the same vector operand joins it as one more row, so the vector is
  // loaded once (the paper's three `dp4 r1.c, v0, c#` become one m4x3-like step).
  void CompileDot(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest) {
    const OpcodeInfo& info = instruction.info();
    const int width = info.dot_width;
    const SourceOperand& vector = instruction.sources[0];
    const SourceOperand& matrix = instruction.sources[OpcodeInfo::kMatrixSource];
    Step step;
    std::array<Operand*, 4 * kMaxRows> group;
    for (int c = 0; c < width; ++c) {
      step.sources[0][c] = ResolveSource(vector, 0, 0, vector.swizzle[c]);
      group[c] = &step.sources[0][c];
    }
    step.negate[0] = vector.negate;
    const OperandKind vector_kind = UnifyKind(std::span(group.data(), width), vector.negate);

    const bool is_matrix = info.kind == ResultKind::kMatrix;
    int rows = 0;
    for (int row = 0; row < (is_matrix ? info.matrix_rows : 1); ++row) {
      const std::uint16_t lane = is_matrix ? dest[row] : FirstLane(dest);
      if (lane == kNoLane) continue;
      for (int c = 0; c < width; ++c) {
        step.sources[1 + rows][c] = ResolveSource(matrix, 1, row, matrix.swizzle[c]);
        group[rows * width + c] = &step.sources[1 + rows][c];
      }
      step.negate[1 + rows] = matrix.negate;
      step.dest[rows++] = lane;
    }
    const OperandKind row_kind = UnifyKind(std::span(group.data(), rows * width), matrix.negate);
    const int kinds = static_cast<int>(vector_kind) + kOperandKinds * static_cast<int>(row_kind);

    const bool single = !is_matrix && std::count(dest.begin(), dest.end(), kNoLane) == 3 &&
                        instruction.dest.reg.file != RegisterFile::kAddress && !instruction.dest.saturate;
    if (single && TryJoinPreviousDot(step, width, kinds)) return;
    step.kernel = kernels_.dot[width - 3][rows - 1][kinds];
    steps_.push_back(step);
    fusable_candidate_ = true;
    fusable_width_ = width;
    fusable_rows_ = rows;
    fusable_kinds_ = kinds;
    if (!is_matrix) {
      AddReplicas(dest);
      fusable_candidate_ = std::count(dest.begin(), dest.end(), kNoLane) == 3 &&
                           instruction.dest.reg.file != RegisterFile::kAddress;
    }
  }

  bool TryJoinPreviousDot(const Step& step, int width, int kinds) {
    if (!fusable_dot_ || gathers_ != decltype(gathers_){} || !abs_steps_.empty() || fusable_rows_ >= kMaxRows) {
      return false;
    }
    Step& previous = plan_.steps.back();
    if (fusable_width_ != width || fusable_kinds_ != kinds || previous.negate[0] != step.negate[0]) return false;
    for (int c = 0; c < width; ++c) {
      if (!(previous.sources[0][c] == step.sources[0][c])) return false;
    }
    // The joined row reads its sources before the earlier rows store (one kernel loads first), so
    // it must not read what they write.
    for (int s = 0; s < 2; ++s) {
      for (int c = 0; c < width; ++c) {
        const Operand& operand = step.sources[s][c];
        for (int row = 0; row < fusable_rows_; ++row) {
          if (operand.is_array && operand.index == previous.dest[row]) return false;
        }
      }
    }
    previous.sources[1 + fusable_rows_] = step.sources[1];
    previous.negate[1 + fusable_rows_] = step.negate[1];
    previous.dest[fusable_rows_] = step.dest[0];
    ++fusable_rows_;
    previous.kernel = kernels_.dot[width - 3][fusable_rows_ - 1][kinds];
    fusable_candidate_ = true;
    return true;
  }

  void CompileVector(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest) {
    Step step;
    for (int s = 0; s < instruction.info().source_count(); ++s) {
      const SourceOperand& source = instruction.sources[s];
      for (int c = 0; c < 4; ++c) step.sources[s][c] = ResolveSource(source, s, 0, source.swizzle[c]);
      step.negate[s] = source.negate;
    }
    step.kernel = kernels_.vector[static_cast<int>(instruction.opcode)];
    step.dest = dest;
    steps_.push_back(step);
  }

  // One step: the kernel samples (vm/core/texture_sampling.h) and stores through s#'s swizzle. The
  // LOD, src0.w, is not read: with one level it picks level 0 whatever it is.
  void CompileTexldl(const Instruction& instruction, const std::array<std::uint16_t, 4>& dest) {
    const SourceOperand& coordinate = instruction.sources[0];
    const SourceOperand& sampler = instruction.sources[1];
    Step step;
    for (int c = 0; c < 2; ++c) step.sources[0][c] = ResolveSource(coordinate, 0, 0, coordinate.swizzle[c]);
    step.negate[0] = coordinate.negate;
    for (int c = 0; c < 4; ++c) step.sources[1][c] = Operand{static_cast<std::uint32_t>(sampler.swizzle[c]), false};
    step.base = sampler.reg.index;
    step.kernel = kernels_.texture;
    step.dest = dest;
    steps_.push_back(step);
  }

  using OperandLanes = std::array<std::array<std::array<std::uint16_t, 4>, kMaxRows>, kMaxSources>;
  const KernelTable& kernels_;
  const int temp_count_;
  const int address_lanes_;  // a0's lanes: 1 (vs_1_1's a0.x) or 4
  BatchPlan plan_;
  std::vector<Step> steps_;      // the current instruction's steps, after its gathers and _abs steps
  std::vector<Step> abs_steps_;  // the current instruction's _abs steps, after its gathers
  std::array<std::array<bool, 4>, semantics::kLaterModelTempCount> temp_written_{};
  std::array<std::array<std::uint16_t, 4>, semantics::kLaterModelTempCount> temp_lanes_;
  OperandLanes gather_lanes_;
  OperandLanes abs_lanes_;
  std::array<std::array<std::uint8_t, kMaxRows>, kMaxSources> gathers_{};   // components to gather
  std::array<std::array<std::uint8_t, kMaxRows>, kMaxSources> abs_done_{};  // components with an _abs step
  std::array<std::array<int, kMaxRows>, kMaxSources> gather_base_{};
  std::array<std::array<std::uint8_t, kMaxRows>, kMaxSources> gather_address_lane_{};
  std::array<std::uint16_t, 4> address_value_lanes_;
  std::array<bool, 4> address_written_{};
  std::vector<std::array<std::uint16_t, 4>> predicate_lanes_;
  std::vector<std::array<bool, 4>> predicate_written_;
  // A predicated instruction's results before its predicated write.
  std::array<std::uint16_t, 4> predicated_lanes_ = {kNoLane, kNoLane, kNoLane, kNoLane};
  std::array<bool, 4 * kInputRegisterCount> inputs_read_{};
  // The last step is a dot step another dp may join (see CompileDot).
  bool fusable_dot_ = false;
  bool fusable_candidate_ = false;
  int fusable_width_ = 0, fusable_rows_ = 0, fusable_kinds_ = 0;
};

}  // namespace

BatchPlan BuildBatchPlan(const Program& program, const KernelTable& kernels) {
  return PlanBuilder(kernels, program).Build(program);
}

}  // namespace vs11::batch
