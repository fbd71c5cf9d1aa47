// An option as the reader of a message knows it: a tool's user by its flag (`--max-error 2`), a
// Python caller by the argument (`max_error=2`). The jobs (irradiance/jobs) serve both, so their
// option errors name the option through these.
#pragma once

#include <string>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

namespace vs11::irradiance {

enum class OptionNaming { kFlag, kPythonArgument };

// The tool's flag `flag`, given without dashes ("max-error"), as `naming` spells it: "--max-error"
// or "max_error".
inline std::string OptionName(OptionNaming naming, std::string_view flag) {
  if (naming == OptionNaming::kFlag) return fmt::format("--{}", flag);
  std::string name(flag);
  for (char& c : name) c = c == '-' ? '_' : c;
  return name;
}

// A name from OptionName with its value, as it would be written: "--layout cube", "layout='cube'".
template <class T>
std::string OptionWithValue(std::string_view name, const T& value) {
  if (name.starts_with("--")) return fmt::format("{} {}", name, value);
  if constexpr (std::is_convertible_v<const T&, std::string_view>) return fmt::format("{}='{}'", name, value);
  return fmt::format("{}={}", name, value);
}

}  // namespace vs11::irradiance
