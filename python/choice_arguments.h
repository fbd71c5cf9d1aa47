// Python arguments whose value is a NameTable's choice (vm/core/name_table.h): parsed by the same
// table as the tools' flags, so a bad name raises ValueError listing the same names
// ("layout='x': unknown layout 'x' (use auto, faces, ...)"), and the tables' names offered to Python.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <pybind11/pybind11.h>

#include "vm/core/name_table.h"

namespace vs11::python {

template <class Enum, std::size_t N>
Enum ChoiceArgument(const NameTable<Enum, N>& table, std::string_view argument, const std::string& name) {
  if (std::optional<Enum> value = table.Find(name)) return *value;
  throw pybind11::value_error(fmt::format("{}='{}': {}", argument, name, table.UnknownName(name)));
}

// As above, where `none_name` ("auto") means nullopt.
template <class Enum, std::size_t N>
std::optional<Enum> ChoiceArgument(const NameTable<Enum, N>& table, std::string_view argument, const std::string& name,
                                   std::string_view none_name) {
  if (name == none_name) return std::nullopt;
  if (std::optional<Enum> value = table.Find(name)) return value;
  throw pybind11::value_error(fmt::format("{}='{}': {}", argument, name, table.UnknownName(name, none_name)));
}

// The table's names as a tuple (with `first` ahead of them when given), for a module attribute.
template <class Enum, std::size_t N>
pybind11::tuple ChoiceNames(const NameTable<Enum, N>& table, std::string_view first = {}) {
  pybind11::list names;
  if (!first.empty()) names.append(std::string(first));
  for (const std::string& name : table.Names()) names.append(name);
  return pybind11::tuple(names);
}

}  // namespace vs11::python
