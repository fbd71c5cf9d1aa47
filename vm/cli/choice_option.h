// Command-line options whose value is a NameTable's choice (vm/core/name_table.h): the flag is parsed
// straight into the enum, an unknown name is a usage error that lists the names ("--window: unknown
// window 'x' (use none, hanning or lanczos)"), and the default shown in --help is the value's name.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/core/name_table.h"

namespace vs11::cli {

// Accepts the table's names and, when `first` is given, that name too.
template <class Enum, std::size_t N>
CLI::Validator ChoiceValidator(const NameTable<Enum, N>& table, std::string_view first = {}) {
  return CLI::Validator(
      [&table, first](std::string& text) {
        return (!first.empty() && text == first) || table.Find(text) ? std::string() : table.UnknownName(text, first);
      },
      "");
}

// `--flag NAME` into `value`.
template <class Enum, std::size_t N>
CLI::Option* AddChoiceOption(CLI::App& app, const std::string& flag, Enum& value, const NameTable<Enum, N>& table,
                             const std::string& description) {
  CLI::Option* option = app.add_option_function<std::string>(
      flag, [&value, &table](const std::string& text) { value = *table.Find(text); }, description);
  return option->check(ChoiceValidator(table))->default_str(std::string(table.Name(value)));
}

// `--flag NAME` into an optional `value`, where the name `none_name` ("auto") means nullopt.
template <class Enum, std::size_t N>
CLI::Option* AddChoiceOption(CLI::App& app, const std::string& flag, std::optional<Enum>& value,
                             const NameTable<Enum, N>& table, std::string_view none_name,
                             const std::string& description) {
  CLI::Option* option = app.add_option_function<std::string>(
      flag, [&value, &table](const std::string& text) { value = table.Find(text); }, description);
  return option->check(ChoiceValidator(table, none_name))
      ->default_str(std::string(value ? table.Name(*value) : none_name));
}

// `--flag A,B` (comma-separated or repeated) appended to `values`.
template <class Enum, std::size_t N>
CLI::Option* AddChoiceListOption(CLI::App& app, const std::string& flag, std::vector<Enum>& values,
                                 const NameTable<Enum, N>& table, const std::string& description) {
  CLI::Option* option = app.add_option_function<std::vector<std::string>>(
      flag,
      [&values, &table](const std::vector<std::string>& texts) {
        for (const std::string& text : texts) values.push_back(*table.Find(text));
      },
      description);
  return option->check(ChoiceValidator(table))->delimiter(',');
}

}  // namespace vs11::cli
