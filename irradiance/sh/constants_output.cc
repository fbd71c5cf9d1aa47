// Emitters for the seven Table 1 registers. See constants_output.h.
#include "irradiance/sh/constants_output.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <vector>

#include <fmt/format.h>

#include "vm/io/vertex_io.h"

namespace vs11::irradiance {
namespace {

constexpr int kRegisterCount = static_cast<int>(SevenConstants::kNames.size());

// "kCAr" for "cAr".
std::string CppName(int index) {
  std::string name = SevenConstants::kNames[index];
  name[0] = 'C';
  return "k" + name;
}

// Each line of `text` prefixed with `prefix` (empty lines get the prefix without trailing blank).
std::string PrefixLines(std::string_view text, std::string_view prefix) {
  std::string out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    if (line.empty()) {
      std::string_view trimmed = prefix;
      while (!trimmed.empty() && trimmed.back() == ' ') trimmed.remove_suffix(1);
      out += trimmed;
    } else {
      out += prefix;
      out += line;
    }
    out += '\n';
    if (end == text.size()) break;
    start = end + 1;
  }
  return out;
}

// A C++ float literal that reads back as exactly `value`.
std::string CppFloatLiteral(float value) {
  if (std::isnan(value)) return "std::numeric_limits<float>::quiet_NaN()";
  if (std::isinf(value)) {
    return value > 0 ? "std::numeric_limits<float>::infinity()"
                     : "-std::numeric_limits<float>::infinity()";
  }
  std::string text = FormatFloat(value);
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text + "f";
}

}  // namespace

std::string RegisterDefText(std::span<const NamedRegister> registers, int base_register,
                            std::string_view header_comment) {
  assert(base_register >= 0);
  std::string out;
  if (!header_comment.empty()) out += PrefixLines(header_comment, "; ");
  std::vector<std::string> defs;
  std::size_t width = 0;
  for (std::size_t i = 0; i < registers.size(); ++i) {
    const glm::vec4& v = registers[i].value;
    defs.push_back(fmt::format("def c{}, {}, {}, {}, {}", base_register + static_cast<int>(i), FormatFloat(v.x),
                               FormatFloat(v.y), FormatFloat(v.z), FormatFloat(v.w)));
    width = std::max(width, defs.back().size());
  }
  for (std::size_t i = 0; i < registers.size(); ++i) {  // comments in one column
    out += fmt::format("{:<{}}  ; {} = {}\n", defs[i], width, registers[i].name, registers[i].contents);
  }
  return out;
}

std::string ConstantsDefText(const SevenConstants& constants, int base_register,
                             std::string_view header_comment) {
  std::vector<NamedRegister> registers;
  for (int i = 0; i < kRegisterCount; ++i) {
    registers.push_back({SevenConstants::kNames[i], Table1Contents(i), constants.registers[i]});
  }
  return RegisterDefText(registers, base_register, header_comment);
}

std::string ConstantsCppHeader(const SevenConstants& constants, std::string_view namespace_name,
                               std::string_view header_comment) {
  bool needs_limits = false;
  for (const glm::vec4& v : constants.registers) {
    for (int c = 0; c < 4; ++c) needs_limits = needs_limits || !std::isfinite(v[c]);
  }
  std::string out;
  if (!header_comment.empty()) out += PrefixLines(header_comment, "// ");
  out += "#pragma once\n\n";
  if (needs_limits) out += "#include <limits>\n\n";
  if (!namespace_name.empty()) out += fmt::format("namespace {} {{\n\n", namespace_name);
  for (int i = 0; i < kRegisterCount; ++i) {
    const glm::vec4& v = constants.registers[i];
    out += fmt::format("inline constexpr float {}[4] = {{{}, {}, {}, {}}};  // {} = {}\n", CppName(i),
                       CppFloatLiteral(v.x), CppFloatLiteral(v.y), CppFloatLiteral(v.z),
                       CppFloatLiteral(v.w), SevenConstants::kNames[i], Table1Contents(i));
  }
  if (!namespace_name.empty()) out += fmt::format("\n}}  // namespace {}\n", namespace_name);
  return out;
}

nlohmann::ordered_json ConstantsJson(const SevenConstants& constants) {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (int i = 0; i < kRegisterCount; ++i) {
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    for (int c = 0; c < 4; ++c) {
      const float value = constants.registers[i][c];
      values.push_back(std::isfinite(value) ? nlohmann::ordered_json(value)
                                            : nlohmann::ordered_json(nullptr));
    }
    out[SevenConstants::kNames[i]] = std::move(values);
  }
  return out;
}

}  // namespace vs11::irradiance
