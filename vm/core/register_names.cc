#include "vm/core/register_names.h"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace vs11 {

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
  if (prefix == 0 || prefix == name.size()) return std::nullopt;
  const std::string_view digits = name.substr(prefix);
  int index = -1;
  auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
  if (ec != std::errc() || end != digits.data() + digits.size() || index < 0) return std::nullopt;
  return index;
}

}  // namespace vs11
