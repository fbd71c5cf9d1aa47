#include "vm/asm/temporary_dataflow.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string_view>
#include <utility>

#include "vm/asm/validator.h"

namespace vs11 {
namespace {

constexpr int kMaxTemps = 32;  // vs_2_x and vs_3_0 (vm/core/shader_model.h); vs_2_0 has 12
// a0 (written by mova) and p0 (by setp) follow the temporaries in the same lane sets.
constexpr int kA0Slot = kMaxTemps;
constexpr int kP0Slot = kMaxTemps + 1;
constexpr int kSlots = kMaxTemps + 2;
constexpr std::uint8_t kAllLanes = WriteMask::kAllLanes;
constexpr std::uint8_t kLaneX = 1 << 0;
constexpr std::uint8_t kLaneW = 1 << 3;
constexpr std::uint8_t kLanesXyz = 0x7;
using Lanes = std::array<std::uint8_t, kSlots>;

// What is known about the temporaries at one point of the program, over the paths that reach it.
struct FlowState {
  bool reachable = true;
  Lanes must{};       // written on every path
  Lanes may{};        // written on some path
  Lanes clobbered{};  // left undefined by sgn on some path, and not written since
};

FlowState Unreachable() {
  FlowState state;
  state.reachable = false;
  return state;
}

// Where two paths join.
FlowState Merge(const FlowState& a, const FlowState& b) {
  if (!a.reachable) return b;
  if (!b.reachable) return a;
  FlowState joined;
  for (int r = 0; r < kSlots; ++r) {
    joined.must[r] = a.must[r] & b.must[r];
    joined.may[r] = a.may[r] | b.may[r];
    joined.clobbered[r] = a.clobbered[r] | b.clobbered[r];
  }
  return joined;
}

// Register lanes that swizzled lanes `swizzled` come from.
std::uint8_t ThroughSwizzle(std::uint8_t swizzled, Swizzle swizzle) {
  std::uint8_t lanes = 0;
  for (int lane = 0; lane < 4; ++lane) {
    if (swizzled & (1 << lane)) lanes |= static_cast<std::uint8_t>(1 << swizzle[lane]);
  }
  return lanes;
}

// Lanes of source `s` the instruction reads (the header says where each rule comes from).
std::uint8_t ReadLanes(const Instruction& instruction, int s) {
  const SourceOperand& source = instruction.sources[s];
  const std::uint8_t mask = instruction.dest.mask.bits() & kAllLanes;
  switch (instruction.opcode) {
    case Opcode::kCrs: {
      std::uint8_t swizzled = 0;
      constexpr std::array<std::uint8_t, 3> kCrossNeeds = {0x6, 0x5, 0x3};  // x: y z, y: x z, z: x y
      for (int lane = 0; lane < 3; ++lane) {
        if (mask & (1 << lane)) swizzled |= kCrossNeeds[lane];
      }
      return ThroughSwizzle(swizzled, source.swizzle);
    }
    case Opcode::kNrm: return ThroughSwizzle(kLanesXyz | mask, source.swizzle);
    case Opcode::kPow: return ThroughSwizzle(kLaneW, source.swizzle);
    case Opcode::kSincos: return ThroughSwizzle(s == 0 ? kLaneW : kAllLanes, source.swizzle);
    case Opcode::kTexldl: return ThroughSwizzle(kAllLanes, source.swizzle);
    case Opcode::kIfc:
    case Opcode::kBreakc: return ThroughSwizzle(kLaneX, source.swizzle);  // as the engines compare
    default: return ConsumedLanes(instruction.info(), s, instruction.dest.mask, source.swizzle);
  }
}

std::string LaneSuffix(std::uint8_t lanes) {
  std::string text = ".";
  for (int lane = 0; lane < 4; ++lane) {
    if (lanes & (1 << lane)) text += kLaneLetters[lane];
  }
  return text;
}

constexpr int kMainProgram = -1;

class TemporaryDataflow {
 public:
  explicit TemporaryDataflow(const Program& program)
      : program_(program),
        temp_count_(std::min(RegisterCount(RegisterFile::kTemp, program.model()), kMaxTemps)) {
    FindSections();
  }

  std::vector<TemporaryReadFinding> Run() {
    Walk(kMainProgram, FlowState{}, true);
    std::vector<int> order;
    std::set<int> seen;
    CalleesFirstOrder(kMainProgram, seen, order);
    for (auto it = order.rbegin(); it != order.rend(); ++it) {  // callers before their callees
      const auto entry = entries_.find(*it);
      if (*it != kMainProgram && entry != entries_.end()) Walk(*it, entry->second, true);
    }
    std::stable_sort(findings_.begin(), findings_.end(),
                     [](const Pending& a, const Pending& b) { return a.finding.index < b.finding.index; });
    std::vector<TemporaryReadFinding> findings;
    for (Pending& pending : findings_) findings.push_back(std::move(pending.finding));
    return findings;
  }

 private:
  struct Section {
    int begin;
    int end;
  };
  struct Frame {
    bool loop;
    FlowState entry;
    FlowState then_out = Unreachable();
    bool has_else = false;
    FlowState breaks = Unreachable();
    std::size_t first_finding = 0;
  };
  struct Pending {
    TemporaryReadFinding finding;
    Lanes missing{};  // the lanes no path wrote (errors), to say which a loop writes later
    bool first_iteration_noted = false;
  };
  struct Effect {
    Lanes must{};
    Lanes may{};
    Lanes clobbered{};
  };

  const Instruction& At(int index) const { return program_.instructions[index]; }
  int Size() const { return static_cast<int>(program_.instructions.size()); }

  // The main program runs up to the first label; a subroutine from its label to the next (the first
  // definition of a label counts, as the validator reports the others).
  void FindSections() {
    int start = 0;
    int owner = kMainProgram;
    for (int i = 0; i <= Size(); ++i) {
      if (i < Size() && At(i).opcode != Opcode::kLabel) continue;
      sections_.emplace(owner, Section{start, i});
      if (i == Size()) break;
      owner = At(i).sources[0].reg.index;
      start = i + 1;
      if (sections_.count(owner)) owner = kDuplicate;
    }
    sections_.erase(kDuplicate);
    for (const auto& [owner, section] : sections_) {
      for (int i = section.begin; i < section.end; ++i) {
        if (At(i).opcode == Opcode::kCall || At(i).opcode == Opcode::kCallnz) {
          callees_[owner].push_back(At(i).sources[0].reg.index);
        }
      }
    }
  }

  // Post-order of the call graph from `owner`; a recursive call (an error the validator reports) is cut.
  void CalleesFirstOrder(int owner, std::set<int>& seen, std::vector<int>& order) {
    if (!seen.insert(owner).second || !sections_.count(owner)) return;
    for (int callee : callees_[owner]) CalleesFirstOrder(callee, seen, order);
    order.push_back(owner);
  }

  // What a subroutine writes on every path through it and on some, from an empty state.
  const Effect& EffectOf(int label) {
    static const Effect kNone;
    if (const auto known = effects_.find(label); known != effects_.end()) return known->second;
    // A call chain deeper than any model allows (the validator reports it) adds nothing: this bounds the
    // recursion a hostile program could cause.
    constexpr std::size_t kDeepestChain = 8;
    if (!sections_.count(label) || computing_.size() >= kDeepestChain || !computing_.insert(label).second) {
      return kNone;
    }
    const FlowState out = Walk(label, FlowState{}, false);
    computing_.erase(label);
    Effect& effect = effects_[label];
    if (out.reachable) effect = Effect{out.must, out.may, out.clobbered};
    return effect;
  }

  // Follows the paths through one section from `entry`; returns the state where it returns.
  FlowState Walk(int owner, FlowState entry, bool report) {
    const Section section = sections_.at(owner);
    std::vector<Frame> frames;
    FlowState state = std::move(entry);
    FlowState out = Unreachable();
    const auto innermost_loop = [&]() -> Frame* {
      for (auto it = frames.rbegin(); it != frames.rend(); ++it) {
        if (it->loop) return &*it;
      }
      return nullptr;
    };
    for (int i = section.begin; i < section.end; ++i) {
      const Instruction& instruction = At(i);
      const bool conditional = instruction.predicated;
      if (report) CheckReads(i, state, owner);
      switch (instruction.opcode) {
        case Opcode::kIf:
        case Opcode::kIfc: frames.push_back(Frame{false, state}); break;
        case Opcode::kElse:
          if (!frames.empty() && !frames.back().loop && !frames.back().has_else) {
            frames.back().then_out = std::exchange(state, frames.back().entry);
            frames.back().has_else = true;
          }
          break;
        case Opcode::kEndif:
          if (!frames.empty() && !frames.back().loop) {
            state = Merge(frames.back().has_else ? frames.back().then_out : frames.back().entry, state);
            frames.pop_back();
          }
          break;
        case Opcode::kLoop:
        case Opcode::kRep: frames.push_back(Frame{true, state, Unreachable(), false, Unreachable(), findings_.size()}); break;
        case Opcode::kEndloop:
        case Opcode::kEndrep:
          if (!frames.empty() && frames.back().loop) {
            const FlowState body_end = Merge(state, frames.back().breaks);
            // Loops nested deeper than any model allows (an error already) are not annotated, which keeps
            // a hostile nesting from rescanning the findings at every level.
            constexpr std::size_t kDeepestNoted = 8;
            if (frames.size() <= kDeepestNoted) NoteFirstIteration(frames.back().first_finding, body_end);
            state = Merge(frames.back().entry, body_end);  // zero iterations, or any number
            frames.pop_back();
          }
          break;
        case Opcode::kBreak:
        case Opcode::kBreakc:
        case Opcode::kBreakp:
          if (Frame* loop = innermost_loop()) {
            loop->breaks = Merge(loop->breaks, state);
            if (instruction.opcode == Opcode::kBreak && !conditional) state = Unreachable();
          }
          break;
        case Opcode::kRet:
          out = Merge(out, state);
          state = Unreachable();
          break;
        case Opcode::kCall:
        case Opcode::kCallnz: Call(instruction, state, report, conditional || instruction.opcode == Opcode::kCallnz); break;
        default:
          Clobber(instruction, state);
          Write(instruction, state);
          break;
      }
    }
    return Merge(out, state);
  }

  void Call(const Instruction& instruction, FlowState& state, bool report, bool conditional) {
    if (!state.reachable) return;
    const int target = instruction.sources[0].reg.index;
    if (report) {
      const auto [entry, first] = entries_.emplace(target, state);
      if (!first) entry->second = Merge(entry->second, state);
    }
    const Effect& effect = EffectOf(target);
    for (int r = 0; r < kSlots; ++r) {
      if (!conditional) {
        state.must[r] |= effect.must[r];
        state.clobbered[r] &= ~effect.must[r];
      }
      state.may[r] |= effect.may[r];
      state.clobbered[r] |= effect.clobbered[r];
    }
  }

  // The slot a write lands in: a temporary, a0 (mova) or p0 (setp); -1 for any other.
  int WrittenSlot(const Instruction& instruction) const {
    const RegisterRef& reg = instruction.dest.reg;
    if (!instruction.info().has_dest() || !instruction.info().is_executable() || reg.relative) return -1;
    if (reg.file == RegisterFile::kAddress) return kA0Slot;
    if (reg.file == RegisterFile::kPredicate) return kP0Slot;
    return reg.file == RegisterFile::kTemp && reg.index >= 0 && reg.index < temp_count_ ? reg.index : -1;
  }

  void Write(const Instruction& instruction, FlowState& state) const {
    const int slot = WrittenSlot(instruction);
    if (!state.reachable || slot < 0) return;
    const std::uint8_t mask = instruction.dest.mask.bits() & kAllLanes;
    if (!instruction.predicated) {
      state.must[slot] |= mask;
      state.clobbered[slot] &= ~mask;
    }
    state.may[slot] |= mask;
  }

  // sgn's src1 and src2: "their contents are undefined after execution" (D3D9 reference, sgn - vs).
  void Clobber(const Instruction& instruction, FlowState& state) const {
    if (!state.reachable || instruction.opcode != Opcode::kSgn) return;
    for (int s = 1; s < 3; ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file == RegisterFile::kTemp && !reg.relative && reg.index >= 0 && reg.index < temp_count_) {
        state.clobbered[reg.index] = kAllLanes;
      }
    }
  }

  void CheckReads(int index, const FlowState& state, int owner) {
    const Instruction& instruction = At(index);
    const OpcodeInfo& info = instruction.info();
    if (!state.reachable || !info.is_executable()) return;
    Lanes none{}, partly{}, some_paths{}, clobbered{};
    for (int s = 0; s < SourceCount(info, program_.model()); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file != RegisterFile::kTemp || reg.relative) continue;
      if (instruction.opcode == Opcode::kSgn && s > 0) continue;  // scratch registers
      const std::uint8_t lanes = ReadLanes(instruction, s);
      for (int row = 0; row < info.registers_read(s); ++row) {
        const int r = reg.index + row;
        if (r < 0 || r >= temp_count_) continue;  // the validator reports the register
        const std::uint8_t unwritten = lanes & ~state.may[r];
        (state.may[r] == 0 ? none : partly)[r] |= unwritten;
        some_paths[r] |= lanes & ~state.must[r] & ~unwritten;
        clobbered[r] |= lanes & state.clobbered[r] & state.must[r];
      }
    }
    const std::string context = owner == kMainProgram ? "" : fmt::format(" (on entry to l{}: no call writes it first)", owner);
    const std::string some_context =
        owner == kMainProgram ? "" : fmt::format(", or a call of l{} without it", owner);
    Add(index, Severity::kError, DiagnosticCode::kUninitializedRegister, none,
        [&](const std::string& list, bool one) {
          return fmt::format("reads {} before {} written on any path{}; a temporary must be written before it is "
                             "read (D3D9 reference, temporary registers), so write {} earlier in the program",
                             list, one ? "it is" : "they are", context, one ? "it" : "them");
        });
    Add(index, Severity::kError, DiagnosticCode::kUninitializedLanes, partly, [&](const std::string& list, bool) {
      return fmt::format("reads {}, which no path writes before this read{}; D3D9 refuses a read of uninitialized "
                         "components: write those lanes earlier in the program",
                         list, context);
    });
    Add(index, Severity::kWarning, DiagnosticCode::kUninitializedLanes, some_paths,
        [&](const std::string& list, bool one) {
          return fmt::format("reads {}, which only some paths write before this read (an if side, a loop that may "
                             "run no iteration, a predicated write{}); on the others {} undefined: write {} on every "
                             "path",
                             list, some_context, one ? "it is" : "they are", one ? "it" : "them");
        });
    Add(index, Severity::kWarning, DiagnosticCode::kUninitializedLanes, clobbered, [&](const std::string& list, bool one) {
      return fmt::format("reads {}, which an earlier sgn left undefined (on some path at least): sgn's src1 and src2 "
                         "are scratch registers whose contents are undefined afterwards (D3D9 reference, sgn - vs); "
                         "write {} again before reading",
                         list, one ? "it" : "them");
    });
    CheckRegisterReads(index, state, context, some_context);
  }

  // a0 and p0 as an instruction reads them: a0's lane in each index through a0 (c#[a0.y], vs_3_0's
  // o#[a0.x]), p0's lane in a condition (if p0.x, callnz l#, p0.y, breakp p0.z), and the p0 lanes a
  // predicated instruction's written lanes take through its swizzle. The same paths as the temporaries:
  // lanes no path writes are an error, lanes some paths write a warning. a0's findings carry
  // kAddressNotWritten, as vs_1_1's rule (validator.cc) does.
  void CheckRegisterReads(int index, const FlowState& state, const std::string& context,
                          const std::string& some_context) {
    const Instruction& instruction = At(index);
    Lanes read{};
    const auto through_a0 = [&](const RegisterRef& reg) {
      if (reg.relative && reg.address.file == RegisterFile::kAddress) read[kA0Slot] |= 1 << (reg.address.swizzle_bits & 3);
    };
    for (int s = 0; s < SourceCount(instruction.info(), program_.model()); ++s) {
      const SourceOperand& source = instruction.sources[s];
      through_a0(source.reg);
      if (source.reg.file == RegisterFile::kPredicate) read[kP0Slot] |= 1 << source.swizzle[0];
    }
    if (instruction.info().has_dest()) through_a0(instruction.dest.reg);
    if (instruction.predicated) {
      const std::uint8_t lanes = instruction.info().has_dest() ? instruction.dest.mask.bits() & kAllLanes : kAllLanes;
      read[kP0Slot] |= ThroughSwizzle(lanes, instruction.predicate.swizzle);
    }
    for (int slot : {kA0Slot, kP0Slot}) {
      const std::uint8_t unwritten = read[slot] & ~state.may[slot];
      const std::uint8_t some_paths = read[slot] & ~state.must[slot] & ~unwritten;
      const bool address = slot == kA0Slot;
      const std::string_view writer = address ? "mova" : "setp";
      Lanes lanes{};
      if (unwritten != 0) {
        lanes[slot] = unwritten;
        const bool none = state.may[slot] == 0;
        Add(index, Severity::kError,
            address ? DiagnosticCode::kAddressNotWritten
                    : (none ? DiagnosticCode::kUninitializedRegister : DiagnosticCode::kUninitializedLanes),
            lanes, [&](const std::string& list, bool) {
              return fmt::format("reads {}, which no path writes before this read{}{}; write {} with {} earlier in "
                                 "the program",
                                 list, none ? "" : fmt::format(" ({} wrote other lanes)", writer), context,
                                 address ? "a0" : "p0", writer);
            });
      }
      if (some_paths != 0) {
        lanes[slot] = some_paths;
        Add(index, Severity::kWarning, address ? DiagnosticCode::kAddressNotWritten : DiagnosticCode::kUninitializedLanes,
            lanes, [&](const std::string& list, bool) {
              return fmt::format("reads {}, which only some paths write before this read (an if side, a loop that "
                                 "may run no iteration, a predicated {}{}); on the others it is undefined: write it "
                                 "on every path",
                                 list, writer, some_context);
            });
      }
    }
  }

  static std::string SlotName(int slot) {
    if (slot == kA0Slot) return "a0";
    if (slot == kP0Slot) return "p0";
    return fmt::format("r{}", slot);
  }

  template <typename Describe>
  void Add(int index, Severity severity, DiagnosticCode code, const Lanes& lanes, Describe describe) {
    std::vector<std::string> names;
    for (int r = 0; r < kSlots; ++r) {
      if (lanes[r] != 0) names.push_back(fmt::format("{}{}", SlotName(r), LaneSuffix(lanes[r])));
    }
    if (names.empty()) return;
    Pending pending{TemporaryReadFinding{index, severity, code, describe(fmt::format("{}", fmt::join(names, ", ")),
                                                                          names.size() == 1)}};
    if (severity == Severity::kError) pending.missing = lanes;
    findings_.push_back(std::move(pending));
  }

  // An error in a loop body about lanes the body writes later: the first iteration reads them unwritten.
  void NoteFirstIteration(std::size_t first, const FlowState& body_end) {
    for (std::size_t f = first; f < findings_.size(); ++f) {
      Pending& pending = findings_[f];
      if (pending.first_iteration_noted || pending.finding.severity != Severity::kError) continue;
      bool written_later = false;
      for (int r = 0; r < kSlots; ++r) written_later |= (pending.missing[r] & body_end.may[r]) != 0;
      if (!written_later) continue;
      pending.first_iteration_noted = true;
      pending.finding.message += "; the loop body writes it only after this read, so its first iteration reads it "
                                 "unwritten";
    }
  }

  static constexpr int kDuplicate = -2;

  const Program& program_;
  const int temp_count_;
  std::map<int, Section> sections_;  // kMainProgram or a label number
  std::map<int, std::vector<int>> callees_;
  std::map<int, FlowState> entries_;  // each subroutine's state merged over its calls
  std::map<int, Effect> effects_;
  std::set<int> computing_;
  std::vector<Pending> findings_;
};

}  // namespace

std::vector<TemporaryReadFinding> FindUnwrittenTemporaryReads(const Program& program) {
  return TemporaryDataflow(program).Run();
}

}  // namespace vs11
