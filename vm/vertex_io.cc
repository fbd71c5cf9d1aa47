#include "vm/vertex_io.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

namespace vs11 {
namespace {

struct Cursor {
  std::string_view line;
  std::size_t pos = 0;

  void SkipSeparators() {
    while (pos < line.size() && (std::isspace(static_cast<unsigned char>(line[pos])) || line[pos] == ',')) ++pos;
  }
  bool AtEnd() {
    SkipSeparators();
    return pos >= line.size();
  }
  int column() const { return static_cast<int>(pos) + 1; }
  std::optional<float> Number() {
    SkipSeparators();
    std::size_t end = pos;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end])) && line[end] != ',') ++end;
    std::string_view token = line.substr(pos, end - pos);
    if (!token.empty() && (token.back() == 'f' || token.back() == 'F') && token.size() > 1 &&
        token.find_first_of("xX") == std::string_view::npos) {
      token.remove_suffix(1);
    }
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    float value = 0.0f;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
    pos = end;
    return value;
  }
};

std::string_view StripComment(std::string_view line) {
  for (std::string_view marker : {";", "//", "#"}) {
    std::size_t at = line.find(marker);
    if (at != std::string_view::npos) line = line.substr(0, at);
  }
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.remove_suffix(1);
  return line;
}

std::vector<std::string_view> SplitLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

// Parses "c12" at the cursor; returns the index or an error text.
std::optional<int> ConstantRegister(Cursor& cursor, std::string& error) {
  cursor.SkipSeparators();
  if (cursor.pos >= cursor.line.size() || std::tolower(static_cast<unsigned char>(cursor.line[cursor.pos])) != 'c') {
    error = "expected a constant register such as c12";
    return std::nullopt;
  }
  ++cursor.pos;
  int index = 0;
  auto [ptr, ec] = std::from_chars(cursor.line.data() + cursor.pos, cursor.line.data() + cursor.line.size(), index);
  if (ec != std::errc() || ptr == cursor.line.data() + cursor.pos) {
    error = "expected a register number after 'c'";
    return std::nullopt;
  }
  cursor.pos = static_cast<std::size_t>(ptr - cursor.line.data());
  return index;
}

// Reads up to four numbers into `values`; returns an error text on failure.
std::optional<std::string> ReadValues(Cursor& cursor, Vec4f& values, int& column) {
  values = {};
  for (int i = 0; i < 4 && !cursor.AtEnd(); ++i) {
    column = cursor.column();
    std::optional<float> number = cursor.Number();
    if (!number) return "expected a number";
    values[i] = *number;
  }
  column = cursor.column();
  if (!cursor.AtEnd()) return "more than four values";
  return std::nullopt;
}

}  // namespace

void ParseConstantsText(std::string_view text, const std::string& file_name, ConstantBank& bank,
                        Diagnostics& diagnostics) {
  std::vector<std::string_view> lines = SplitLines(text);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    Cursor cursor{StripComment(lines[n])};
    if (cursor.AtEnd()) continue;
    int line_number = static_cast<int>(n) + 1;
    auto error_at = [&](int column, std::string message) {
      diagnostics.Error({file_name, line_number, column}, std::move(message));
    };
    std::string_view rest = cursor.line.substr(cursor.pos);
    bool is_def = rest.size() > 3 && (rest.substr(0, 3) == "def" || rest.substr(0, 3) == "DEF") &&
                  std::isspace(static_cast<unsigned char>(rest[3]));
    if (is_def) cursor.pos += 3;
    std::string error;
    int register_column = (cursor.SkipSeparators(), cursor.column());
    std::optional<int> index = ConstantRegister(cursor, error);
    if (!index) {
      error_at(register_column, error + (is_def ? "" : " (lines are `def c#, x, y, z, w` or `c# = x y z w`)"));
      continue;
    }
    cursor.SkipSeparators();
    if (!is_def) {
      if (cursor.pos >= cursor.line.size() || cursor.line[cursor.pos] != '=') {
        error_at(cursor.column(), "expected '=' after the register");
        continue;
      }
      ++cursor.pos;
    }
    Vec4f values;
    int column = 0;
    if (std::optional<std::string> value_error = ReadValues(cursor, values, column)) {
      error_at(column, *value_error);
      continue;
    }
    if (*index < 0 || *index >= bank.size()) {
      error_at(register_column, fmt::format("c{} is beyond the {} constant registers", *index, bank.size()));
      continue;
    }
    bank[*index] = values;
  }
}

std::optional<std::string> ParseConstantAssignment(std::string_view text, ConstantBank& bank) {
  Diagnostics diagnostics;
  ParseConstantsText(text, "--const", bank, diagnostics);
  if (diagnostics.HasErrors()) return diagnostics.all().front().message + " in '" + std::string(text) + "'";
  return std::nullopt;
}

std::vector<Vec4f> ParseVertexCsv(std::string_view text, const std::string& file_name, Diagnostics& diagnostics) {
  std::vector<Vec4f> rows;
  std::vector<std::string_view> lines = SplitLines(text);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    Cursor cursor{lines[n]};
    if (cursor.AtEnd()) continue;
    Vec4f row = kDefaultInput;
    int count = 0;
    int column = 0;
    bool ok = true;
    while (!cursor.AtEnd()) {
      column = cursor.column();
      std::optional<float> number = cursor.Number();
      if (!number || count == 4) {
        ok = false;
        break;
      }
      row[count++] = *number;
    }
    if (!ok) {
      bool header = rows.empty() && count == 0 && n == 0;
      if (!header) {
        diagnostics.Error({file_name, static_cast<int>(n) + 1, column},
                          count == 4 ? "more than four numbers in a row" : "expected a number");
      }
      continue;
    }
    rows.push_back(row);
  }
  return rows;
}

std::string FormatFloat(float value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);  // fmt prints the shortest round-trip form
}

std::string FormatOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix) {
  std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);
  std::vector<std::string> header = prefix.header;
  std::vector<std::pair<int, int>> columns;
  for (int slot : outputs.registers()) {
    for (int lane = 0; lane < 4; ++lane) {
      if (!written[slot].has(lane)) continue;
      header.push_back(fmt::format("{}.{}", OutputSlotName(slot), kLaneLetters[lane]));
      columns.emplace_back(slot, lane);
    }
  }
  std::string out = fmt::format("{}\n", fmt::join(header, ","));
  for (std::size_t i = 0; i < outputs.count(); ++i) {
    std::vector<std::string> cells;
    if (i < prefix.rows.size()) {
      for (float v : prefix.rows[i]) cells.push_back(FormatFloat(v));
    }
    for (auto [slot, lane] : columns) cells.push_back(FormatFloat(outputs.lane(slot, lane)[i]));
    out += fmt::format("{}\n", fmt::join(cells, ","));
  }
  return out;
}

}  // namespace vs11
