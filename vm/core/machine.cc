#include "vm/core/machine.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "vm/core/checked_arithmetic.h"
#include "vm/core/static_flow.h"

namespace vs11 {

namespace {

// What no engine runs of a later model yet.
Status LaterModelRefusal(const Program& program, std::string_view engine) {
  const ShaderModel model = program.model();
  for (std::size_t i = 0; i < program.instructions.size(); ++i) {
    const Instruction& instruction = program.instructions[i];
    const SourceLoc loc = program.LocOf(static_cast<int>(i));
    const std::string where = fmt::format("instruction {}{}", i + 1, loc.line > 0 ? fmt::format(", line {}", loc.line) : "");
    if (instruction.opcode == Opcode::kDcl && instruction.dest.reg.file == RegisterFile::kSampler &&
        instruction.sampler_type != kSampler2d) {
      return Failure(DiagnosticCode::kEngineUnavailable,
                     fmt::format("the {} engine cannot run this program ({}): s{} is declared dcl_{}, and only 2D vertex "
                                 "textures (dcl_2d) are modelled",
                                 engine, where, instruction.dest.reg.index,
                                 instruction.sampler_type >= 0 && instruction.sampler_type < static_cast<int>(kSamplerTypeNames.size())
                                     ? kSamplerTypeNames[static_cast<std::size_t>(instruction.sampler_type)]
                                     : "?"),
                     loc);
    }
    if (instruction.opcode != Opcode::kTexldl || std::ranges::find(kTexldlEngines, engine) != kTexldlEngines.end()) continue;
    std::string engines;  // "ref, batch and jit"
    for (std::size_t e = 0; e < kTexldlEngines.size(); ++e) {
      engines += fmt::format("{}{}", e == 0 ? "" : e + 1 == kTexldlEngines.size() ? " and " : ", ", kTexldlEngines[e]);
    }
    return Failure(DiagnosticCode::kEngineUnavailable,
                   fmt::format("the {} engine cannot run texldl ({}): vertex textures run on the {} engines", engine,
                               where, engines),
                   loc);
  }
  if (model != ShaderModel::kVs30) return {};
  const auto slots = DeclaredOutputSlots(program);
  for (const Instruction& instruction : program.instructions) {
    if (instruction.opcode != Opcode::kDcl || instruction.dest.reg.file != RegisterFile::kTexCoordOut) continue;
    const int reg = instruction.dest.reg.index;
    if (reg >= 0 && reg < kOutputRegisterCountVs30 && slots[static_cast<std::size_t>(reg)]) continue;
    const std::string_view usage = instruction.usage >= 0 && instruction.usage < static_cast<int>(kDeclUsageNames.size())
                                       ? kDeclUsageNames[static_cast<std::size_t>(instruction.usage)]
                                       : "?";
    return Failure(DiagnosticCode::kEngineUnavailable,
                   fmt::format("the {} engine cannot run this vs_3_0 program: o{} is declared dcl_{}{}, which has no "
                               "output of the engine (oPos, oFog, oPts, oD0-oD1, oT0-oT7)",
                               engine, reg, usage, instruction.usage_index == 0 ? "" : std::to_string(instruction.usage_index)));
  }
  return {};
}

}  // namespace

Status EngineRefusal(const Program& program, std::string_view engine) {
  const ShaderModel model = program.model();
  if (Info(model).runs) return {};
  const bool specialises = std::ranges::find(kStaticFlowEngines, engine) != kStaticFlowEngines.end();
  if (engine != kLaterModelEngine && !specialises) {
    return Failure(DiagnosticCode::kEngineUnavailable,
                   fmt::format("the {} engine cannot run {} programs yet (they assemble, disassemble and validate, "
                               "and run on the {} engine, and on batch, jit and gl; "
                               "the {} engine runs only vs_1_1 programs)",
                               engine, ShaderModelName(model), kLaterModelEngine, engine));
  }
  if (Status refusal = LaterModelRefusal(program, engine); !refusal || !specialises) return refusal;
  return StaticFlowRefusal(program, engine);
}

ConstantBank ApplyDefinitions(const Program& program, ConstantBank api_constants) {
  for (const Instruction& instruction : program.instructions) {
    const int index = instruction.dest.reg.index;
    if (instruction.opcode == Opcode::kDefi) {
      if (index >= 0 && index < kIntegerConstantCount) {
        for (int c = 0; c < 4; ++c) api_constants.integer(index)[c] = static_cast<std::int32_t>(instruction.def_bits[c]);
      }
      continue;
    }
    if (instruction.opcode == Opcode::kDefb) {
      if (index >= 0 && index < kBooleanConstantCount) api_constants.SetBoolean(index, instruction.def_bits[0] != 0);
      continue;
    }
    if (instruction.opcode != Opcode::kDef) continue;
    if (index >= 0 && index < api_constants.size()) {
      std::array<float, 4> values = instruction.def_values();
      api_constants[index] = {values[0], values[1], values[2], values[3]};
    }
  }
  return api_constants;
}

std::optional<int> OutputSlotOf(const RegisterRef& reg) {
  switch (reg.file) {
    case RegisterFile::kRasterOut:
      if (reg.index >= 0 && reg.index <= kRasterOutPointSize) return reg.index;  // same order as OutputSlot
      return std::nullopt;
    case RegisterFile::kAttributeOut:
      if (reg.index >= 0 && reg.index < kColorOutputCount) return static_cast<int>(OutputSlot::kDiffuse) + reg.index;
      return std::nullopt;
    case RegisterFile::kTexCoordOut:
      if (reg.index >= 0 && reg.index < kTexCoordOutputCount) return static_cast<int>(OutputSlot::kTexCoord0) + reg.index;
      return std::nullopt;
    default: return std::nullopt;
  }
}

std::optional<int> OutputSlotOfUsage(int usage, int index) {
  // D3DDECLUSAGE values (kDeclUsageNames).
  constexpr int kPosition = 0, kPointSize = 4, kTexCoord = 5, kPositionT = 9, kColor = 10, kFog = 11;
  switch (usage) {
    case kPosition:
    case kPositionT: return index == 0 ? std::optional(static_cast<int>(OutputSlot::kPosition)) : std::nullopt;
    case kColor:
      return index >= 0 && index < kColorOutputCount ? std::optional(static_cast<int>(OutputSlot::kDiffuse) + index)
                                                     : std::nullopt;
    case kTexCoord:
      return index >= 0 && index < kTexCoordOutputCount
                 ? std::optional(static_cast<int>(OutputSlot::kTexCoord0) + index)
                 : std::nullopt;
    case kPointSize: return index == 0 ? std::optional(static_cast<int>(OutputSlot::kPointSize)) : std::nullopt;
    case kFog: return index == 0 ? std::optional(static_cast<int>(OutputSlot::kFog)) : std::nullopt;
    default: return std::nullopt;
  }
}

std::array<std::optional<int>, kOutputRegisterCountVs30> DeclaredOutputSlots(const Program& program) {
  std::array<std::optional<int>, kOutputRegisterCountVs30> slots{};
  for (const Instruction& instruction : program.instructions) {
    const int reg = instruction.dest.reg.index;
    if (instruction.opcode != Opcode::kDcl || instruction.dest.reg.file != RegisterFile::kTexCoordOut) continue;
    if (reg >= 0 && reg < kOutputRegisterCountVs30) {
      slots[static_cast<std::size_t>(reg)] = OutputSlotOfUsage(instruction.usage, instruction.usage_index);
    }
  }
  return slots;
}

std::string OutputSlotName(int slot) {
  static constexpr std::array<const char*, 5> kFixedNames = {"oPos", "oFog", "oPts", "oD0", "oD1"};
  if (slot < static_cast<int>(OutputSlot::kTexCoord0)) return kFixedNames[static_cast<std::size_t>(slot)];
  return fmt::format("oT{}", slot - static_cast<int>(OutputSlot::kTexCoord0));
}

std::optional<int> OutputSlotFromName(std::string_view name) {
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    std::string candidate = OutputSlotName(slot);
    if (candidate.size() == name.size() &&
        std::equal(candidate.begin(), candidate.end(), name.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
        })) {
      return slot;
    }
  }
  return std::nullopt;
}

Vec4f UnwrittenOutputValue(int slot) {
  if (slot == static_cast<int>(OutputSlot::kDiffuse)) return {1.0f, 1.0f, 1.0f, 1.0f};
  if (slot == static_cast<int>(OutputSlot::kSpecular)) return {0.0f, 0.0f, 0.0f, 1.0f};
  return {};
}

std::array<WriteMask, kOutputSlotCount> WrittenOutputLanes(const Program& program) {
  std::array<std::uint8_t, kOutputSlotCount> bits{};
  if (program.model() == ShaderModel::kVs30) {
    // o# through its declaration; o[aL + n] may reach every declared output.
    const auto declared = DeclaredOutputSlots(program);
    for (const Instruction& instruction : program.instructions) {
      const RegisterRef& reg = instruction.dest.reg;
      if (!instruction.info().is_executable() || !instruction.info().has_dest() || reg.file != RegisterFile::kTexCoordOut) continue;
      for (int o = 0; o < kOutputRegisterCountVs30; ++o) {
        const std::optional<int> slot = declared[static_cast<std::size_t>(o)];
        if (slot && (reg.relative || reg.index == o)) bits[*slot] |= instruction.dest.mask.bits();
      }
    }
  } else {
    for (const Instruction& instruction : program.instructions) {
      if (!instruction.info().is_executable() || !instruction.info().has_dest()) continue;
      if (std::optional<int> slot = OutputSlotOf(instruction.dest.reg)) bits[*slot] |= instruction.dest.mask.bits();
    }
  }
  std::array<WriteMask, kOutputSlotCount> masks;
  for (int i = 0; i < kOutputSlotCount; ++i) masks[i] = WriteMask(bits[i]);
  return masks;
}

VertexArrays::VertexArrays(std::size_t count, std::span<const int> registers, int register_space)
    : count_(count), slot_of_(static_cast<std::size_t>(register_space), -1) {
  int slots = 0;
  for (int reg : registers) {
    if (reg >= 0 && reg < register_space && slot_of_[reg] < 0) slot_of_[reg] = slots++;
  }
  constexpr std::size_t kFloatsPerLine = 16;
  // `count` may come from a caller's array (a NumPy view broadcast to 2^62 rows costs it nothing):
  // a size that wraps around would allocate a few bytes and write far beyond them.
  const std::optional<std::size_t> padded = CheckedAdd<std::size_t>(count, 2 * kFloatsPerLine);
  const std::optional<std::size_t> bytes = padded ? CheckedMul<std::size_t>(*padded, 4 * sizeof(float) * slots) : std::nullopt;
  if (!bytes || *bytes / sizeof(float) > data_.max_size()) {
    throw std::length_error(fmt::format("{} vertices: the vertex arrays would not fit in the address space", count));
  }
  stride_ = (count + kFloatsPerLine - 1) / kFloatsPerLine * kFloatsPerLine;
  if (count > kFloatsPerLine && (stride_ / kFloatsPerLine) % 2 == 0) stride_ += kFloatsPerLine;
  data_.assign(static_cast<std::size_t>(slots) * 4 * stride_, 0.0f);
  uniform_.assign(static_cast<std::size_t>(slots) * 4, 0.0f);
  borrowed_.assign(static_cast<std::size_t>(slots) * 4, StridedLane{});
}

void VertexArrays::Borrow(int reg, const std::array<StridedLane, 4>& lanes) {
  assert(reg >= 0 && reg < static_cast<int>(slot_of_.size()) && !has(reg));
  // Borrowed slots come after the arrays' own, which alone have room in data_.
  slot_of_[reg] = static_cast<int>(borrowed_.size() / 4);
  for (const StridedLane& lane : lanes) {
    assert(lane.base != nullptr);
    borrowed_.push_back(lane);
    uniform_.push_back(lane.stride == 0 ? std::optional<float>(*lane.base) : std::nullopt);
  }
}

void VertexArrays::FillUniform(int reg, int component, float value) {
  std::fill_n(lane(reg, component), count_, value);
  uniform_[Index(reg, component)] = value;
}

std::vector<int> VertexArrays::registers() const {
  std::vector<int> result;
  for (int reg = 0; reg < static_cast<int>(slot_of_.size()); ++reg) {
    if (slot_of_[reg] >= 0) result.push_back(reg);
  }
  return result;
}

VertexArrays MakeInputArrays(std::size_t count, std::span<const int> input_registers) {
  VertexArrays arrays(count, input_registers, kInputRegisterCount);
  for (int reg : arrays.registers()) {
    for (int c = 0; c < 4; ++c) arrays.FillUniform(reg, c, kDefaultInput[c]);
  }
  return arrays;
}

VertexArrays MakeOutputArrays(std::size_t count, const Program& program) {
  std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  std::vector<int> slots;
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    if (written[slot].bits() != 0) slots.push_back(slot);
  }
  // Every lane starts as uniform 0, the value of a lane the program leaves alone in a register it
  // writes (oD0.a beside oD0.rgb): the engines need not store those again on every run.
  return VertexArrays(count, slots, kOutputSlotCount);
}

void FillWithNaN(VertexArrays& outputs) {
  for (int reg : outputs.registers()) {
    for (int c = 0; c < 4; ++c) {
      std::fill_n(outputs.lane(reg, c), outputs.count(), std::numeric_limits<float>::quiet_NaN());
    }
  }
}

}  // namespace vs11
