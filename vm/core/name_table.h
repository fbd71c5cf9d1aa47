// The one place a choice's names live: a constexpr table of {value, name, one-line description} per
// enum, from which come the parser (name -> value, or an error that lists the valid names), the name
// of a value, the lists for --help and error messages, and (vm/cli/choice_option.h, the Python
// bindings) the tools' and the module's choices. A new choice is a new row; nothing else repeats it.
//
//   inline constexpr NameTable kWindowNames("window", {
//       Choice(ShWindow::kNone, "none"),
//       Choice(ShWindow::kHanning, "hanning", "of --window-width bands")});
//   kWindowNames.Find("hanning")  -> ShWindow::kHanning;  kWindowNames.Name(ShWindow::kNone) -> "none"
//   kWindowNames.Parse("x")       -> throws std::invalid_argument("unknown window 'x' (use none or hanning)")
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace vs11 {

template <class Enum>
struct NamedChoice {
  Enum value;
  std::string_view name;
  std::string_view description;  // one line for --help; empty where the name says it all
};

// A row of a NameTable (a function, so that the table's enum type is deduced from its rows).
template <class Enum>
constexpr NamedChoice<Enum> Choice(Enum value, std::string_view name, std::string_view description = {}) {
  return {value, name, description};
}

template <class Enum, std::size_t N>
class NameTable {
 public:
  // `what` names the choice in messages ("unknown window 'x'"). Names are unique and not empty
  // (checked when the table is built, at compile time for a constexpr table).
  constexpr NameTable(std::string_view what, const NamedChoice<Enum> (&choices)[N]) : what_(what) {
    for (std::size_t i = 0; i < N; ++i) {
      choices_[i] = choices[i];
      if (choices[i].name.empty()) throw std::logic_error("NameTable: an empty name");
      for (std::size_t j = 0; j < i; ++j) {
        if (choices[j].name == choices[i].name || choices[j].value == choices[i].value) {
          throw std::logic_error("NameTable: a name or value given twice");
        }
      }
    }
  }

  constexpr std::string_view what() const { return what_; }
  constexpr const NamedChoice<Enum>* begin() const { return choices_.data(); }
  constexpr const NamedChoice<Enum>* end() const { return choices_.data() + N; }
  static constexpr std::size_t size() { return N; }

  // The value named `name` (exact spelling), or nullopt.
  constexpr std::optional<Enum> Find(std::string_view name) const {
    for (const NamedChoice<Enum>& choice : choices_) {
      if (choice.name == name) return choice.value;
    }
    return std::nullopt;
  }

  // The value named `name`; std::invalid_argument(UnknownName(name)) for any other name (pybind11
  // raises it as ValueError).
  Enum Parse(std::string_view name) const {
    if (std::optional<Enum> value = Find(name)) return *value;
    throw std::invalid_argument(UnknownName(name));
  }

  // The name of `value`, which is a row of the table (asserted).
  constexpr std::string_view Name(Enum value) const { return Row(value).name; }
  constexpr std::string_view Description(Enum value) const { return Row(value).description; }

  // "a, b or c"; `first`, when given, leads the list (a name the caller accepts besides the table's,
  // such as "auto").
  std::string List(std::string_view first = {}) const {
    std::vector<std::string_view> names;
    if (!first.empty()) names.push_back(first);
    for (const NamedChoice<Enum>& choice : choices_) names.push_back(choice.name);
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) {
      out += i == 0 ? "" : i + 1 == names.size() ? " or " : ", ";
      out += names[i];
    }
    return out;
  }

  // "unknown window 'x' (use none, hanning or lanczos)".
  std::string UnknownName(std::string_view name, std::string_view first = {}) const {
    return "unknown " + std::string(what_) + " '" + std::string(name) + "' (use " + List(first) + ")";
  }

  // For --help: every name with its description in parentheses where it has one,
  // "none, hanning (of --window-width bands) or lanczos".
  std::string Help() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i) {
      out += i == 0 ? "" : i + 1 == N ? " or " : ", ";
      out += choices_[i].name;
      if (!choices_[i].description.empty()) out += " (" + std::string(choices_[i].description) + ")";
    }
    return out;
  }

  // The names in table order (the Python module's choices).
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const NamedChoice<Enum>& choice : choices_) names.emplace_back(choice.name);
    return names;
  }

 private:
  constexpr const NamedChoice<Enum>& Row(Enum value) const {
    for (const NamedChoice<Enum>& choice : choices_) {
      if (choice.value == value) return choice;
    }
    assert(false && "a value without a row in its NameTable");
    return choices_[0];
  }

  std::string_view what_;
  std::array<NamedChoice<Enum>, N> choices_{};
};

}  // namespace vs11
