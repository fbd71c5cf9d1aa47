#include "vm/asm/read_ports.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <iterator>

#include "vm/asm/disassembler.h"

namespace vs11 {
namespace {

// The sources read together: one group for ordinary instructions, one per expanded row of m*x* (row i
// reads s0 and the register s1 + i: §3.4).
std::vector<std::vector<RegisterRef>> ReadPortGroups(const Instruction& instruction, ShaderModel model) {
  const OpcodeInfo& info = instruction.info();
  std::vector<std::vector<RegisterRef>> groups;
  if (info.kind == ResultKind::kMatrix) {
    for (int row = 0; row < info.matrix_rows; ++row) {
      RegisterRef matrix_row = instruction.sources[OpcodeInfo::kMatrixSource].reg;
      matrix_row.index += row;
      groups.push_back({instruction.sources[0].reg, matrix_row});
    }
    return groups;
  }
  // sincos d, s, c1, c2 (vs_2_0, vs_2_x): c1 and c2 are the macro's constants, not ports it reads.
  const int counted = instruction.opcode == Opcode::kSincos ? 1 : SourceCount(info, model);
  groups.emplace_back();
  for (int s = 0; s < counted; ++s) groups.back().push_back(instruction.sources[s].reg);
  return groups;
}

std::vector<RegisterRef> DistinctRegisters(const std::vector<RegisterRef>& group, RegisterFile file) {
  std::vector<RegisterRef> distinct;
  for (const RegisterRef& reg : group) {
    if (reg.file == file && std::find(distinct.begin(), distinct.end(), reg) == distinct.end()) {
      distinct.push_back(reg);
    }
  }
  return distinct;
}

// The limits in words ("one", "three").
std::string CountWord(int count) {
  constexpr std::array<std::string_view, 4> kWords = {"no", "one", "two", "three"};
  return count < static_cast<int>(kWords.size()) ? std::string(kWords[count]) : std::to_string(count);
}

}  // namespace

std::vector<ReadPortViolation> FindReadPortViolations(const Instruction& instruction, ShaderModel model) {
  const auto groups = ReadPortGroups(instruction, model);
  const bool in_macro = groups.size() > 1;
  std::vector<ReadPortViolation> violations;
  for (const ReadPortLimit& limit : kReadPortLimits) {
    const int ports = limit.ports[static_cast<int>(model)];
    const int reads = limit.reads[static_cast<int>(model)];
    for (int row = 0; row < static_cast<int>(groups.size()); ++row) {
      std::vector<RegisterRef> distinct = DistinctRegisters(groups[row], limit.file);
      if (ports > 0 && static_cast<int>(distinct.size()) > ports) {
        violations.push_back(ReadPortViolation{&limit, false, ports, row, in_macro, std::move(distinct)});
        break;  // one report per register type and instruction
      }
      std::vector<RegisterRef> operands;
      std::copy_if(groups[row].begin(), groups[row].end(), std::back_inserter(operands),
                   [&](const RegisterRef& reg) { return reg.file == limit.file; });
      if (reads > 0 && static_cast<int>(operands.size()) > reads) {
        violations.push_back(ReadPortViolation{&limit, true, reads, row, in_macro, std::move(operands)});
        break;
      }
    }
  }
  return violations;
}

std::string DescribeReadPortViolation(const ReadPortViolation& violation, ShaderModel model) {
  const std::string where =
      violation.in_macro ? fmt::format("row {} of the macro expansion (§3.4) ", violation.row) : "";
  std::vector<std::string> names;
  bool absolute_and_relative = false;
  for (const RegisterRef& reg : violation.registers) {
    names.push_back(FormatSource(SourceOperand{reg, Swizzle(), false}, Syntax::kDx9, model));
    for (const RegisterRef& other : violation.registers) {
      absolute_and_relative |= reg.index == other.index && reg.relative != other.relative;
    }
  }
  // Unconfirmed (§10.8): we count an absolute and a relative constant as two operands.
  const std::string note = absolute_and_relative ? " (an absolute and a relative constant count as two)" : "";
  const std::string source =
      model == ShaderModel::kVs11
          ? ""
          : fmt::format(" (the read-port limit of the D3D9 reference's {} registers page)", ShaderModelName(model));
  const int count = static_cast<int>(violation.registers.size());
  if (violation.reads) {
    return fmt::format("{}reads {} registers {} times ({}); {} allows {} {} reads per instruction (the reads/inst "
                       "limit of the D3D9 reference's {} registers page) — copy one into a temporary first",
                       where, violation.limit->role, count, fmt::join(names, ", "), ShaderModelName(model),
                       violation.allowed, violation.limit->role, ShaderModelName(model));
  }
  const int excess = count - violation.allowed;
  return fmt::format("{}reads {} different {} registers ({}){}; {} allows {} per instruction{} — copy {} into {} first",
                     where, count == 2 ? "two" : std::to_string(count), violation.limit->role, fmt::join(names, ", "), note, ShaderModelName(model),
                     CountWord(violation.allowed), source,
                     excess == 1 ? "one of them" : fmt::format("all but {} of them", CountWord(violation.allowed)),
                     excess == 1 ? "a temporary" : "temporaries");
}

}  // namespace vs11
