#include "vm/core/register_names.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace vs11 {
namespace {

std::string_view TrimSpaces(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A register's number: decimal digits only (no sign, no spaces).
std::optional<int> ParseRegisterNumber(std::string_view digits) {
  if (digits.empty() || !std::isdigit(static_cast<unsigned char>(digits.front()))) return std::nullopt;
  int index = -1;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
  if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return index;
}

}  // namespace

std::size_t NumberedRegisterPrefix(std::string_view text, RegisterFile file) {
  for (const RegisterSpelling& spelling : kRegisterSpellings) {
    if (spelling.file != file || spelling.fixed_index != RegisterSpelling::kNumbered) continue;
    const std::string_view prefix = spelling.name;
    if (text.size() >= prefix.size() &&
        std::equal(prefix.begin(), prefix.end(), text.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
        })) {
      return prefix.size();
    }
  }
  return 0;
}

std::optional<int> ParseNumberedRegister(std::string_view name, RegisterFile file) {
  const std::size_t prefix = NumberedRegisterPrefix(name, file);
  if (prefix == 0) return std::nullopt;
  return ParseRegisterNumber(name.substr(prefix));
}

std::optional<int> ParseInputRegister(std::string_view name) {
  const std::optional<int> index = ParseNumberedRegister(TrimSpaces(name), RegisterFile::kInput);
  if (!index || *index >= kInputRegisterCount) return std::nullopt;
  return index;
}

std::optional<int> ParseConstantRegister(std::string_view name) {
  name = TrimSpaces(name);
  const std::size_t prefix = NumberedRegisterPrefix(name, RegisterFile::kConst);
  if (prefix == 0) return std::nullopt;
  std::string_view number = name.substr(prefix);
  if (number.size() >= 2 && number.front() == '[' && number.back() == ']') {
    number = TrimSpaces(number.substr(1, number.size() - 2));
  }
  const std::optional<int> index = ParseRegisterNumber(number);
  if (!index || *index > kMaxConstantIndex) return std::nullopt;
  return index;
}

}  // namespace vs11
