#include "vm/core/static_flow.h"

#include <algorithm>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "vm/core/operands.h"

namespace vs11 {

bool OpensBlock(Opcode op) { return op == Opcode::kIf || op == Opcode::kIfc || op == Opcode::kLoop || op == Opcode::kRep; }
bool ClosesBlock(Opcode op) { return op == Opcode::kEndif || op == Opcode::kEndloop || op == Opcode::kEndrep; }

ControlTable BuildControlTable(const Program& program) {
  const int n = static_cast<int>(program.instructions.size());
  ControlTable table;
  table.partner.assign(static_cast<std::size_t>(n), kNoMatch);
  std::vector<int> open;  // indices of if/loop/rep, and of else in place of its if
  for (int i = 0; i < n; ++i) {
    const Instruction& instruction = program.instructions[static_cast<std::size_t>(i)];
    const Opcode op = instruction.opcode;
    if (op == Opcode::kLabel) {
      const int label = instruction.sources[0].reg.index;
      if (label >= 0 && label < RegisterCount(RegisterFile::kLabel, ShaderModel::kVs30)) {
        if (static_cast<int>(table.label_at.size()) <= label) table.label_at.resize(static_cast<std::size_t>(label) + 1, kNoMatch);
        table.label_at[static_cast<std::size_t>(label)] = i;
      }
      open.clear();  // a subroutine starts afresh
    } else if (OpensBlock(op)) {
      open.push_back(i);
    } else if (op == Opcode::kElse && !open.empty()) {
      table.partner[static_cast<std::size_t>(open.back())] = i;
      open.back() = i;
    } else if (ClosesBlock(op) && !open.empty()) {
      table.partner[static_cast<std::size_t>(open.back())] = i;
      if (op != Opcode::kEndif) table.partner[static_cast<std::size_t>(i)] = open.back();
      open.pop_back();
    }
  }
  return table;
}

StaticFlowKey StaticFlowKeyOf(const ConstantBank& constants) {
  StaticFlowKey key;
  for (int i = 0; i < kIntegerConstantCount; ++i) key.integers[static_cast<std::size_t>(i)] = constants.ReadInteger(i);
  for (int i = 0; i < kBooleanConstantCount; ++i) key.booleans[static_cast<std::size_t>(i)] = constants.ReadBoolean(i);
  key.constant_count = constants.size();
  return key;
}

ConstantBank ModelConstants(const Program& program, ConstantBank api_constants) {
  api_constants.GrowTo(RegisterCount(RegisterFile::kConst, program.model()));
  return ApplyDefinitions(program, std::move(api_constants));
}

namespace {

// Where a read that the reference engine gives 0 (an input or constant past its file, a temporary
// past r31) points in the straight-line program: a constant far below c0, which every engine reads as 0
// with all the rows of a matrix.
constexpr int kZeroRow = -(1 << 20);

constexpr int kComparisonCount = static_cast<int>(kComparisonNames.size()) - 1;  // 1 gt ... 6 le

Diagnostic Refuse(const Program& program, std::size_t i, std::string_view engine, std::string_view why) {
  const SourceLoc loc = program.LocOf(static_cast<int>(i));
  return Failure(DiagnosticCode::kEngineUnavailable,
                 fmt::format("the {} engine cannot run this {} program (instruction {}{}, {}): {}", engine,
                             ShaderModelName(program.model()), i + 1,
                             loc.line > 0 ? fmt::format(", line {}", loc.line) : "",
                             program.instructions[i].info().mnemonic, why),
                 loc);
}

std::optional<std::string> RefusalOf(const Instruction& instruction) {
  if (TakesComparison(instruction.opcode) && (instruction.comparison < 1 || instruction.comparison > kComparisonCount)) {
    return "its comparison is none of gt, eq, ge, lt, ne, le";
  }
  return std::nullopt;  // every row has a kernel (texldl: batch's texture kernel; gl refuses it before)
}

RegisterRef RegisterOfSlot(int slot) {
  if (slot < static_cast<int>(OutputSlot::kDiffuse)) return {RegisterFile::kRasterOut, slot};
  if (slot < static_cast<int>(OutputSlot::kTexCoord0)) {
    return {RegisterFile::kAttributeOut, slot - static_cast<int>(OutputSlot::kDiffuse)};
  }
  return {RegisterFile::kTexCoordOut, slot - static_cast<int>(OutputSlot::kTexCoord0)};
}

// The reference engine's control walk (vm/engines/reference_flow.cc) for every vertex at once: the
// instructions it would run, in order, each with aL resolved. A static condition (b#, i#) takes one
// way; a per-vertex one (if_comp, if p0, break_comp, breakp, callnz p0) takes both, each under an
// execution mask, and every instruction under a mask that is not all vertices is predicated by it.
//
// Masks are predicate registers of the straight-line program, one lane each (x), 1 where a vertex
// runs and 0 where not, as setp writes p0; they are combined with vs_1_1 arithmetic, exact on 1 and
// 0: a & b = min(a, b), a & !b = slt(b, a), !b = sge(0, b). Registers: p0 is the program's, p1 a
// scratch register, and the frame at depth d (an if, loop or call open) owns p(2d) and p(2d + 1).
// Loop trip counts stay static (i#); a vertex that breaks is masked off for the rest of the loop, and
// the iterations run to the count (bounded, as the walk, by the steps and unrolled-length limits).
class Specialiser {
 public:
  Specialiser(const Program& program, const StaticFlowKey& key)
      : program_(program), control_(BuildControlTable(program)), key_(key),
        declared_outputs_(DeclaredOutputSlots(program)) {
    out_.version = semantics::kLaterModelStraightLine;
  }

  Result<Program> Run(std::string_view engine) {
    const int n = static_cast<int>(program_.instructions.size());
    int steps = 0;
    FlowWalk<Specialiser> walk(program_, control_, *this, aL_);
    for (int pc = 0; pc >= 0 && pc < n && !unsupported_; pc = walk.Step(pc)) {
      if (++steps > kMaxStaticFlowSteps) {
        return Failure(DiagnosticCode::kEngineUnavailable,
                       fmt::format("the {} engine cannot specialise this {} program for its integer and boolean "
                                   "constants: it runs more than {} instructions (D3D9's smallest "
                                   "MaxVShaderInstructionsExecuted); the ref engine runs it",
                                   engine, ShaderModelName(program_.model()), kMaxStaticFlowSteps));
      }
      if (static_cast<int>(out_.instructions.size()) > kMaxUnrolledInstructions) {
        return Failure(DiagnosticCode::kEngineUnavailable,
                       fmt::format("the {} engine cannot specialise this {} program for its integer and boolean "
                                   "constants: unrolled it has more than {} instructions, the most the engine "
                                   "compiles; the ref engine runs it",
                                   engine, ShaderModelName(program_.model()), kMaxUnrolledInstructions));
      }
    }
    if (unsupported_) {
      return Failure(DiagnosticCode::kEngineUnavailable,
                     fmt::format("the {} engine cannot run this {} program: {}; the ref engine runs it", engine,
                                 ShaderModelName(program_.model()), *unsupported_));
    }
    return std::move(out_);
  }

 private:
  friend class FlowWalk<Specialiser>;

  // A mask that is known statically, or the predicate register (lane x) that holds it.
  static constexpr int kAllLanes = -1;
  static constexpr int kNoLanes = -2;
  static constexpr int kScratch = 1;
  static constexpr std::uint8_t kLaneX = 1;  // a mask's lane
  // One lane of a predicate register, `!` applied or not: a condition, or a mask read as one.
  struct Term {
    int reg = 0;
    int lane = 0;
    bool negated = false;
  };
  enum class FrameKind : std::uint8_t { kIf, kLoop, kCall };
  struct Frame {
    FrameKind kind;
    int outer;            // the mask when the frame opened
    int taken = kNoLanes;  // if: the vertices that take the if branch; loop: those still looping (kNoLanes: outer)
    int breaks = 0;        // loop: its per-vertex breaks so far; if: its loop's when the if opened
    int loop = -1;         // if: the frame of the loop it is in (-1: none)
    bool at_loop_level = false;  // if: opened where the mask is the loop's
    bool masked = false;         // call: callnz p0
  };

  int Depth() const { return static_cast<int>(frames_.size()); }
  static int Working(int depth) { return 2 * depth; }
  static int Owned(int depth) { return 2 * depth + 1; }

  // ---- the walk's questions ----
  Vec4i Integer(int index) const {
    if (current_ == kNoLanes) return {};  // no vertex runs the loop
    return index >= 0 && index < kIntegerConstantCount ? key_.integers[static_cast<std::size_t>(index)] : Vec4i{};
  }
  Branch Comparison(const Instruction&) const { return current_ == kNoLanes ? Branch::kNever : Branch::kPerVertex; }
  Branch Condition(const SourceOperand& source) const {
    if (current_ == kNoLanes) return Branch::kNever;
    if (source.reg.file == RegisterFile::kPredicate) return Branch::kPerVertex;
    const int index = source.reg.index;
    const bool value = source.reg.file == RegisterFile::kConstBool && index >= 0 && index < kBooleanConstantCount &&
                       key_.booleans[static_cast<std::size_t>(index)];
    return value != source.logical_not ? Branch::kAlways : Branch::kNever;
  }

  // ---- emitting mask arithmetic ----
  static SourceOperand PredicateSource(int reg, Swizzle swizzle) {
    return SourceOperand{RegisterRef{RegisterFile::kPredicate, reg, false, {}}, swizzle, false, false, false};
  }
  void Emit(Opcode op, int dest, std::uint8_t lanes, const SourceOperand& a, const SourceOperand& b) {
    Instruction instruction;
    instruction.opcode = op;
    instruction.dest = DestOperand{RegisterRef{RegisterFile::kPredicate, dest, false, {}}, WriteMask(lanes), false};
    instruction.sources[0] = a;
    instruction.sources[1] = b;
    out_.instructions.push_back(instruction);
  }
  // p[dest].x = mask & term.
  void AndInto(int dest, int mask, Term term) {
    const SourceOperand t = PredicateSource(term.reg, Swizzle::Replicate(term.lane));
    const SourceOperand zero{RegisterRef{RegisterFile::kConst, kZeroRow, false, {}}, Swizzle(), false, false, false};
    if (mask == kAllLanes) {
      if (term.negated) {
        Emit(Opcode::kSge, dest, kLaneX, zero, t);
      } else if (term.reg != dest || term.lane != 0) {
        Emit(Opcode::kMov, dest, kLaneX, t, t);
      }
      return;
    }
    const SourceOperand m = PredicateSource(mask, Swizzle::Replicate(0));
    if (term.negated) {
      Emit(Opcode::kSlt, dest, kLaneX, t, m);
    } else {
      Emit(Opcode::kMin, dest, kLaneX, t, m);
    }
  }
  // The condition of if_comp, break_comp (compared into p1.x), if p0.c, breakp p0.c, callnz p0.c.
  Term ConditionTerm(const Instruction& instruction, const SourceOperand& predicate) {
    if (instruction.opcode != Opcode::kIfc && instruction.opcode != Opcode::kBreakc) {
      return {0, predicate.swizzle[0], predicate.logical_not};  // p0: the reference reads p0 whatever the number
    }
    Instruction setp;
    setp.opcode = Opcode::kSetp;
    setp.comparison = instruction.comparison;
    setp.dest = DestOperand{RegisterRef{RegisterFile::kPredicate, kScratch, false, {}}, WriteMask(kLaneX), false};
    for (int s = 0; s < 2; ++s) {
      setp.sources[s] = instruction.sources[s];
      setp.sources[s].reg = Resolve(instruction.sources[s].reg, 1);
    }
    out_.instructions.push_back(setp);
    return {kScratch, 0, false};
  }
  // The vertices still running the innermost loop, and its frame.
  int LoopFrame() const {
    for (int f = Depth() - 1; f >= 0; --f) {
      if (frames_[static_cast<std::size_t>(f)].kind == FrameKind::kLoop) return f;
    }
    return -1;
  }
  int Looping(int loop) const {
    if (loop < 0) return kAllLanes;
    const Frame& frame = frames_[static_cast<std::size_t>(loop)];
    return frame.taken == kNoLanes ? frame.outer : frame.taken;
  }

  // ---- per-vertex flow ----
  void BeginIf(const Instruction& instruction) {
    const Term condition = ConditionTerm(instruction, instruction.sources[0]);
    const int depth = Depth() + 1;
    AndInto(Owned(depth), current_, condition);
    const int loop = LoopFrame();
    frames_.push_back({FrameKind::kIf, current_, Owned(depth), loop < 0 ? 0 : frames_[static_cast<std::size_t>(loop)].breaks,
                       loop, current_ == Looping(loop)});
    current_ = Owned(depth);
  }
  // The mask at an if's end, or its else branch's: `outer & extra`, less the vertices that broke out
  // of its loop since the if began.
  int Rejoin(const Frame& frame, std::optional<Term> extra, int target) {
    const bool broke = frame.loop >= 0 && frames_[static_cast<std::size_t>(frame.loop)].breaks != frame.breaks;
    if (!extra && !broke) return frame.outer;
    if (!extra && frame.at_loop_level) return Looping(frame.loop);
    int mask = frame.outer;
    if (extra) {
      AndInto(target, mask, *extra);
      mask = target;
    }
    if (broke) {
      AndInto(target, mask, {Looping(frame.loop), 0, false});
      mask = target;
    }
    return mask;
  }
  void Else() {
    const Frame& frame = frames_.back();
    current_ = frame.outer == kNoLanes ? kNoLanes : Rejoin(frame, Term{frame.taken, 0, true}, Working(Depth()));
  }
  void EndIf() {
    const Frame frame = frames_.back();
    frames_.pop_back();
    current_ = frame.outer == kNoLanes ? kNoLanes : Rejoin(frame, std::nullopt, Working(Depth()));
  }

  void LoopEntered() { frames_.push_back({FrameKind::kLoop, current_}); }
  void NextIteration() { current_ = Looping(LoopFrame()); }
  void LoopLeft() {
    current_ = frames_.back().outer;
    frames_.pop_back();
  }

  bool BreakLanes(const Instruction& instruction, Branch branch) {
    if (current_ == kNoLanes) return false;  // a break no vertex reaches
    const int loop = LoopFrame();
    for (int f = loop + 1; f < Depth(); ++f) {
      if (frames_[static_cast<std::size_t>(f)].kind == FrameKind::kCall) {
        unsupported_ = "a break inside a subroutine leaves a loop of its caller";
        return true;
      }
    }
    const int looping = Looping(loop);
    const bool at_loop_level = current_ == looping;
    if (branch == Branch::kAlways && at_loop_level) return true;  // every running vertex leaves
    int breaking = current_;
    if (branch == Branch::kPerVertex) {
      AndInto(kScratch, current_, ConditionTerm(instruction, instruction.sources[0]));
      breaking = kScratch;
    }
    Frame& frame = frames_[static_cast<std::size_t>(loop)];
    AndInto(Owned(loop + 1), looping, {breaking, 0, true});
    frame.taken = Owned(loop + 1);
    ++frame.breaks;
    if (at_loop_level) {
      current_ = frame.taken;
    } else if (branch == Branch::kAlways) {
      current_ = kNoLanes;  // the rest of this branch runs for no vertex
    } else {
      AndInto(Working(Depth()), current_, {breaking, 0, true});
      current_ = Working(Depth());
    }
    return false;
  }

  void EnterCall(const Instruction* masked_by) {
    const int depth = Depth() + 1;
    frames_.push_back({FrameKind::kCall, current_, kNoLanes, 0, -1, false, masked_by != nullptr});
    if (masked_by != nullptr) {
      AndInto(Working(depth), current_, ConditionTerm(*masked_by, masked_by->sources[1]));
      current_ = Working(depth);
    }
  }
  // The validator keeps ret out of every block, so each routine returns with the mask it began with;
  // an unvalidated ret under a per-vertex condition would end the routine for some vertices only.
  void Return() {
    int entry = kAllLanes;
    while (!frames_.empty()) {
      const Frame frame = frames_.back();
      frames_.pop_back();
      if (frame.kind == FrameKind::kIf) unsupported_ = "ret inside an if whose condition is per vertex";
      if (frame.kind == FrameKind::kLoop && frame.taken != kNoLanes) unsupported_ = "ret inside a loop that vertices break";
      if (frame.kind != FrameKind::kCall) continue;
      entry = frame.masked ? Working(Depth() + 1) : frame.outer;
      if (current_ != entry && current_ != kNoLanes && !unsupported_) unsupported_ = "ret under a per-vertex condition";
      current_ = frame.outer;
      return;
    }
    if (current_ != entry && current_ != kNoLanes && !unsupported_) unsupported_ = "ret under a per-vertex condition";
  }

  // The static register a source reads on this iteration; kZeroRow where the reference reads 0.
  RegisterRef Resolve(RegisterRef reg, int rows) const {
    if (reg.relative && reg.address.file == RegisterFile::kLoop) {
      // aL + n in the reference engine's long arithmetic.
      const long index = static_cast<long>(reg.index) + aL_;
      reg = RegisterRef{reg.file, index < kZeroRow || index > key_.constant_count ? kZeroRow : static_cast<int>(index)};
    }
    if (reg.file == RegisterFile::kConst && !reg.relative && (reg.index < 0 || reg.index >= key_.constant_count)) {
      return {RegisterFile::kConst, kZeroRow};  // a matrix's later rows past the bank read 0 as well
    }
    if (reg.file == RegisterFile::kInput && (reg.index < 0 || reg.index + rows > kInputRegisterCount)) {
      return {RegisterFile::kConst, kZeroRow};  // (a matrix of inputs past v15 is not a valid program)
    }
    if (reg.file == RegisterFile::kPredicate) reg.index = 0;  // the reference has p0 alone
    return reg;
  }

  void Execute(const Instruction& instruction) {
    const OpcodeInfo& info = instruction.info();
    if (!info.is_executable() || current_ == kNoLanes) return;  // dcl, def, defi, defb: the engine's
    Instruction out = instruction;
    for (int s = 0; s < info.source_count(); ++s) {
      out.sources[static_cast<std::size_t>(s)].reg = Resolve(instruction.sources[static_cast<std::size_t>(s)].reg, info.registers_read(s));
    }
    RegisterRef& dest = out.dest.reg;
    if (program_.model() == ShaderModel::kVs30 && dest.file == RegisterFile::kTexCoordOut) {
      const long index = dest.index + (dest.relative ? static_cast<long>(aL_) : 0);
      if (index < 0 || index >= kOutputRegisterCountVs30) return;  // the reference writes nothing
      const std::optional<int> slot = declared_outputs_[static_cast<std::size_t>(index)];
      if (!slot) return;
      dest = RegisterOfSlot(*slot);
    }
    if (dest.file == RegisterFile::kPredicate) dest.index = 0;
    out.predicate.reg.index = 0;
    if (current_ != kAllLanes) {
      const SourceOperand mask = PredicateSource(current_, Swizzle::Replicate(0));
      if (out.predicated) {
        // Each lane's predicate and the mask, in the scratch register's lanes.
        Emit(out.predicate.logical_not ? Opcode::kSlt : Opcode::kMin, kScratch, out.dest.mask.bits(),
             PredicateSource(0, out.predicate.swizzle), mask);
        out.predicate = PredicateSource(kScratch, Swizzle());
      } else {
        out.predicate = mask;
      }
      out.predicated = true;
    }
    out_.instructions.push_back(out);
  }

  const Program& program_;
  const ControlTable control_;
  const StaticFlowKey& key_;
  const std::array<std::optional<int>, kOutputRegisterCountVs30> declared_outputs_;
  Program out_;
  int aL_ = 0;
  int current_ = kAllLanes;  // the vertices that run the next instruction
  std::vector<Frame> frames_;
  std::optional<std::string> unsupported_;
};

}  // namespace

Status StaticFlowRefusal(const Program& program, std::string_view engine) {
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    if (std::optional<std::string> why = RefusalOf(program.instructions[i])) return Refuse(program, i, engine, *why);
  }
  return {};
}

Result<Program> SpecialiseStaticFlow(const Program& program, const StaticFlowKey& key, std::string_view engine) {
  return Specialiser(program, key).Run(engine);
}

}  // namespace vs11
