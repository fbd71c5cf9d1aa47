#include "vm/io/vertex_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <system_error>

#include <fmt/format.h>

#include "vm/core/register_names.h"
#include "vm/core/static_flow.h"

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
  // The next value: the text up to a blank or ','. The cursor stays before it (Take moves past it).
  std::string_view Peek() {
    SkipSeparators();
    std::size_t end = pos;
    while (end < line.size() && !std::isspace(static_cast<unsigned char>(line[end])) && line[end] != ',') ++end;
    return line.substr(pos, end - pos);
  }
  void Take(std::string_view token) { pos += token.size(); }
  std::optional<float> Number() {
    const std::string_view whole = Peek();
    std::string_view token = whole;
    if (!token.empty() && (token.back() == 'f' || token.back() == 'F') && token.size() > 1 &&
        token.find_first_of("xX") == std::string_view::npos) {
      token.remove_suffix(1);
    }
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    float value = 0.0f;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
    Take(whole);
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

// The register files a constants line may set, with the def keyword that sets each.
struct ConstantFile {
  RegisterFile file;
  char letter;
  std::string_view keyword;
  int count;  // registers in the bank; 0: the bank's own size (c#)
  std::string_view noun;
};
constexpr std::array kConstantFiles = {
    ConstantFile{RegisterFile::kConst, 'c', "def", 0, "constant"},
    ConstantFile{RegisterFile::kConstInt, 'i', "defi", kIntegerConstantCount, "integer constant"},
    ConstantFile{RegisterFile::kConstBool, 'b', "defb", kBooleanConstantCount, "boolean constant"},
};

// The def keyword ("def", "defi", "defb", any case, then a blank) at the start of `rest`.
const ConstantFile* DefKeyword(std::string_view rest) {
  for (const ConstantFile& file : kConstantFiles) {
    const std::size_t n = file.keyword.size();
    if (rest.size() > n && std::isspace(static_cast<unsigned char>(rest[n])) &&
        std::equal(file.keyword.begin(), file.keyword.end(), rest.begin(),
                   [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); })) {
      return &file;
    }
  }
  return nullptr;
}

struct NamedConstant {
  const ConstantFile* file;
  int index;
};

// Parses "c12", "i3" or "b0" at the cursor; returns it, or the error: kConstantLine where the text
// is no such register, kConstantRegisterRange for a number beyond int.
Result<NamedConstant> ConstantRegister(Cursor& cursor) {
  cursor.SkipSeparators();
  const std::string_view rest = cursor.line.substr(cursor.pos);
  const ConstantFile* file = nullptr;
  std::size_t prefix = 0;
  for (const ConstantFile& candidate : kConstantFiles) {
    if ((prefix = NumberedRegisterPrefix(rest, candidate.file)) != 0) {
      file = &candidate;
      break;
    }
  }
  if (file == nullptr) {
    return Failure(DiagnosticCode::kConstantLine, "expected a constant register such as c12 (or i# or b#)");
  }
  cursor.pos += prefix;
  int index = 0;
  auto [ptr, ec] = std::from_chars(cursor.line.data() + cursor.pos, cursor.line.data() + cursor.line.size(), index);
  if (ec == std::errc::result_out_of_range) {
    const std::size_t digits = static_cast<std::size_t>(ptr - cursor.line.data()) - cursor.pos;
    return Failure(DiagnosticCode::kConstantRegisterRange, fmt::format("{}{} is beyond every constant register",
                                                                       file->letter, cursor.line.substr(cursor.pos, digits)));
  }
  if (ec != std::errc() || ptr == cursor.line.data() + cursor.pos) {
    return Failure(DiagnosticCode::kConstantLine, fmt::format("expected a register number after '{}'", file->letter));
  }
  cursor.pos = static_cast<std::size_t>(ptr - cursor.line.data());
  return NamedConstant{file, index};
}

// Reads up to four numbers into `values`, or says what is wrong (kConstantValue) at `column`.
Status ReadValues(Cursor& cursor, Vec4f& values, int& column) {
  values = {};
  for (int i = 0; i < 4 && !cursor.AtEnd(); ++i) {
    column = cursor.column();
    std::optional<float> number = cursor.Number();
    if (!number) return Failure(DiagnosticCode::kConstantValue, "expected a number");
    values[i] = *number;
  }
  column = cursor.column();
  if (!cursor.AtEnd()) return Failure(DiagnosticCode::kConstantValue, "more than four values");
  return {};
}

// The range of each component of an integer constant, as D3D9's loop instruction reads it (asm
// reference, "loop - vs"): x the iteration count, y aL's first value, z aL's step, w reserved (0).
// rep reads only x, with the same range. The reference engine would clamp the count to [0, 255]
// (vm/core/static_flow.h), so a value outside is refused rather than silently changed.
struct IntegerRange {
  int low, high;
  std::string_view role;
};
constexpr std::array<IntegerRange, 4> kIntegerConstantRanges = {
    IntegerRange{0, kMaxLoopCount, "the loop or rep count"},
    IntegerRange{0, 255, "aL's first value"},
    IntegerRange{-128, 127, "aL's step"},
    IntegerRange{0, 0, "reserved"},
};

// Reads up to four integers into `values` (the rest 0), each in its kIntegerConstantRanges.
Status ReadIntegers(Cursor& cursor, Vec4i& values, int& column) {
  values = {};
  for (int i = 0; i < 4 && !cursor.AtEnd(); ++i) {
    column = cursor.column();
    const std::string_view whole = cursor.Peek();
    std::string_view token = whole;
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    long long value = 0;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size()) {
      return Failure(DiagnosticCode::kConstantValue, "expected an integer");
    }
    const IntegerRange& range = kIntegerConstantRanges[static_cast<std::size_t>(i)];
    if (value < range.low || value > range.high) {
      return Failure(DiagnosticCode::kConstantValue,
                     fmt::format("{} ({}) must be {} to {}, not {}", "xyzw"[i], range.role, range.low, range.high,
                                 whole));
    }
    values[static_cast<std::size_t>(i)] = static_cast<int>(value);
    cursor.Take(whole);
  }
  column = cursor.column();
  if (!cursor.AtEnd()) return Failure(DiagnosticCode::kConstantValue, "more than four values");
  return {};
}

// Reads one boolean: true or false (any case), or 1 or 0.
Status ReadBoolean(Cursor& cursor, bool& value, int& column) {
  const std::string_view token = cursor.Peek();
  column = cursor.column();
  std::string word(token);
  std::transform(word.begin(), word.end(), word.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (word == "true" || word == "1") {
    value = true;
  } else if (word == "false" || word == "0") {
    value = false;
  } else {
    return Failure(DiagnosticCode::kConstantValue, "expected true or false (or 1 or 0)");
  }
  cursor.Take(token);
  column = cursor.column();
  if (!cursor.AtEnd()) return Failure(DiagnosticCode::kConstantValue, "a boolean constant takes one value");
  return {};
}

// Reads the values of `reg` and stores them in `bank`.
Status ReadAndStore(Cursor& cursor, const NamedConstant& reg, ConstantBank& bank, int& column) {
  switch (reg.file->file) {
    case RegisterFile::kConstInt: {
      Vec4i values;
      if (const Status read = ReadIntegers(cursor, values, column); !read) return read;
      bank.integer(reg.index) = values;
      return {};
    }
    case RegisterFile::kConstBool: {
      bool value = false;
      if (const Status read = ReadBoolean(cursor, value, column); !read) return read;
      bank.SetBoolean(reg.index, value);
      return {};
    }
    default: {
      Vec4f values;
      if (const Status read = ReadValues(cursor, values, column); !read) return read;
      bank[reg.index] = values;
      return {};
    }
  }
}

std::vector<int>* AssignedList(AssignedConstants* assigned, RegisterFile file) {
  if (assigned == nullptr) return nullptr;
  if (file == RegisterFile::kConstInt) return &assigned->integers;
  if (file == RegisterFile::kConstBool) return &assigned->booleans;
  return &assigned->floats;
}

}  // namespace

void ParseConstantsText(std::string_view text, const std::string& file_name, ConstantBank& bank,
                        Diagnostics& diagnostics, AssignedConstants* assigned) {
  std::vector<std::string_view> lines = SplitLines(text);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    Cursor cursor{StripComment(lines[n])};
    if (cursor.AtEnd()) continue;
    int line_number = static_cast<int>(n) + 1;
    auto error_at = [&](int column, DiagnosticCode code, std::string message) {
      diagnostics.Error({file_name, line_number, column}, code, std::move(message));
    };
    const ConstantFile* keyword = DefKeyword(cursor.line.substr(cursor.pos));
    if (keyword != nullptr) cursor.pos += keyword->keyword.size();
    int register_column = (cursor.SkipSeparators(), cursor.column());
    const Result<NamedConstant> reg = ConstantRegister(cursor);
    if (!reg) {
      const bool syntax = reg.error().code == DiagnosticCode::kConstantLine;
      error_at(register_column, reg.error().code,
               reg.message() + (keyword != nullptr || !syntax
                                    ? ""
                                    : " (lines are `def c#, x, y, z, w` or `c# = x y z w`, and defi/defb or "
                                      "`i# = x y z w`, `b# = true`)"));
      continue;
    }
    if (keyword != nullptr && keyword != reg->file) {
      error_at(register_column, DiagnosticCode::kConstantLine,
               fmt::format("{} sets {}# registers, not {}{}", keyword->keyword, keyword->letter, reg->file->letter,
                           reg->index));
      continue;
    }
    cursor.SkipSeparators();
    if (keyword == nullptr) {
      if (cursor.pos >= cursor.line.size() || cursor.line[cursor.pos] != '=') {
        error_at(cursor.column(), DiagnosticCode::kConstantLine, "expected '=' after the register");
        continue;
      }
      ++cursor.pos;
    }
    const int count = reg->file->count != 0 ? reg->file->count : bank.size();
    if (reg->index < 0 || reg->index >= count) {
      error_at(register_column, DiagnosticCode::kConstantRegisterRange,
               fmt::format("{}{} is beyond the {} {} registers", reg->file->letter, reg->index, count, reg->file->noun));
      continue;
    }
    int column = 0;
    if (const Status read = ReadAndStore(cursor, *reg, bank, column); !read) {
      error_at(column, read.error().code, read.message());
      continue;
    }
    if (std::vector<int>* list = AssignedList(assigned, reg->file->file)) list->push_back(reg->index);
  }
}

Status ParseConstantAssignment(std::string_view text, ConstantBank& bank, AssignedConstants* assigned) {
  Diagnostics diagnostics;
  ParseConstantsText(text, "--const", bank, diagnostics, assigned);
  if (!diagnostics.HasErrors()) return {};
  Diagnostic first = diagnostics.all().front();
  first.message += " in '" + std::string(text) + "'";
  return first;
}

namespace {

// A cell as a float: decimal or exponent notation, a leading '+', a C-style trailing 'f', and the
// special values inf, -inf and nan (the spec's special values must be feedable).
enum class NumberError { kNone, kNotANumber, kOutOfRange };
NumberError ParseNumber(std::string_view token, float& value) {
  while (!token.empty() && std::isspace(static_cast<unsigned char>(token.front()))) token.remove_prefix(1);
  while (!token.empty() && std::isspace(static_cast<unsigned char>(token.back()))) token.remove_suffix(1);
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return NumberError::kNotANumber;
  auto parse = [&value](std::string_view text) {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ptr != text.data() + text.size()) return NumberError::kNotANumber;
    if (ec == std::errc::result_out_of_range) return NumberError::kOutOfRange;
    return ec == std::errc() ? NumberError::kNone : NumberError::kNotANumber;
  };
  NumberError error = parse(token);
  if (error == NumberError::kNotANumber && token.size() > 1 && (token.back() == 'f' || token.back() == 'F') &&
      std::isdigit(static_cast<unsigned char>(token[token.size() - 2]))) {
    error = parse(token.substr(0, token.size() - 1));
  }
  return error;
}

struct Cell {
  std::string_view text;
  int column = 0;  // 1-based
};

// Cells of a line: separated by `separator` and/or blanks; empty cells between separators skipped.
std::vector<Cell> SplitCells(std::string_view line, char separator) {
  std::vector<Cell> cells;
  std::size_t pos = 0;
  auto is_separator = [&](char c) { return c == separator || std::isspace(static_cast<unsigned char>(c)); };
  while (pos < line.size()) {
    while (pos < line.size() && is_separator(line[pos])) ++pos;
    std::size_t end = pos;
    while (end < line.size() && !is_separator(line[end])) ++end;
    if (end > pos) cells.push_back({line.substr(pos, end - pos), static_cast<int>(pos) + 1});
    pos = end;
  }
  return cells;
}

// The first bad row is the error; later ones only add to its count, so that a file in the wrong
// shape gives one message rather than one per row.
class RowErrors {
 public:
  RowErrors(const std::string& file_name, Diagnostics& diagnostics) : file_(file_name), diagnostics_(diagnostics) {}
  void Add(int line, int column, DiagnosticCode code, std::string message) {
    if (count_++ == 0) first_ = {line, column, code, std::move(message)};
  }
  ~RowErrors() {
    if (count_ == 0) return;
    std::string more = count_ > 1 ? fmt::format(" (and {} more bad rows)", count_ - 1) : "";
    diagnostics_.Error({file_, first_.line, first_.column}, first_.code, first_.message + more);
  }

 private:
  struct First {
    int line = 0, column = 0;
    DiagnosticCode code = DiagnosticCode::kUnclassified;
    std::string message;
  };
  const std::string& file_;
  Diagnostics& diagnostics_;
  int count_ = 0;
  First first_;
};

// Which lane of the vertex each wanted column fills; empty = the row's first 1-4 numbers.
struct ColumnChoice {
  std::vector<std::pair<std::size_t, int>> cell_to_lane;  // (index of the cell in a row, lane)
};

// The lanes the columns `wanted` names fill, or why they cannot (kCsvColumns).
Result<ColumnChoice> ChooseColumns(const std::vector<std::string>& header, std::string_view wanted) {
  auto names = [&header] { return fmt::format("{}", fmt::join(header, ", ")); };
  auto wrong = [](std::string message) { return Failure(DiagnosticCode::kCsvColumns, std::move(message)); };
  if (header.empty()) {
    return wrong(fmt::format("columns '{}' asked for, but the file has no header row naming its columns", wanted));
  }
  ColumnChoice choice;
  bool is_list = wanted.find(',') != std::string_view::npos || wanted.find('.') != std::string_view::npos;
  if (!is_list) {  // a prefix: NAME.x .. NAME.w go to their lanes
    for (std::size_t i = 0; i < header.size(); ++i) {
      for (int lane = 0; lane < 4; ++lane) {
        if (header[i] == fmt::format("{}.{}", wanted, kLaneLetters[lane])) choice.cell_to_lane.emplace_back(i, lane);
      }
    }
    if (choice.cell_to_lane.empty()) {
      return wrong(fmt::format("no column is named {}.x, {}.y, {}.z or {}.w (columns: {})", wanted, wanted, wanted,
                               wanted, names()));
    }
    return choice;
  }
  std::size_t start = 0;
  while (start <= wanted.size()) {
    std::size_t comma = std::min(wanted.find(',', start), wanted.size());
    std::string_view name = wanted.substr(start, comma - start);
    auto found = std::find(header.begin(), header.end(), name);
    if (found == header.end()) {
      return wrong(fmt::format("no column is named '{}' (columns: {})", name, names()));
    }
    if (choice.cell_to_lane.size() == 4) {
      return wrong(fmt::format("more than four columns in '{}': a vertex register has four lanes", wanted));
    }
    choice.cell_to_lane.emplace_back(static_cast<std::size_t>(found - header.begin()),
                                     static_cast<int>(choice.cell_to_lane.size()));
    start = comma + 1;
  }
  return choice;
}

// A data row's cells: their text, and each one's value or why it is not a number.
struct RowCells {
  const std::vector<Cell>& cells;
  const std::vector<float>& values;
  const std::vector<NumberError>& errors;
};

// What is wrong with a data row: the first bad cell the vertex needs.
struct RowProblem {
  int column = 1;
  DiagnosticCode code = DiagnosticCode::kUnclassified;
  std::string message;
};

// Fills the lanes of `row` from the cells `wanted` names ((cell, lane) pairs), or says why it cannot.
std::optional<RowProblem> FillVertex(const RowCells& row_cells, const std::vector<std::pair<std::size_t, int>>& wanted,
                                     const std::vector<std::string>& header, std::size_t line_length, Vec4f& row) {
  const std::vector<Cell>& cells = row_cells.cells;
  for (auto [cell, lane] : wanted) {
    if (cell >= cells.size()) {
      return RowProblem{static_cast<int>(line_length) + 1, DiagnosticCode::kCsvMissingCell,
                        fmt::format("the row has {} cells; column '{}' is cell {}", cells.size(), header[cell], cell + 1)};
    }
    if (row_cells.errors[cell] != NumberError::kNone) {
      return RowProblem{cells[cell].column, DiagnosticCode::kCsvNumber,
                        row_cells.errors[cell] == NumberError::kOutOfRange
                            ? fmt::format("'{}' is beyond the float range", cells[cell].text)
                            : fmt::format("expected a number, found '{}'", cells[cell].text)};
    }
    if (lane >= 4) {
      return RowProblem{cells[cell].column, DiagnosticCode::kCsvTooManyValues,
                        fmt::format("{} numbers in a row: a vertex register holds at most four; name the columns to "
                                    "read with v#=FILE:NAME (the lanes NAME.x..NAME.w) or v#=FILE:COL1,COL2,...",
                                    cells.size())};
    }
    row[lane] = row_cells.values[cell];
  }
  return std::nullopt;
}

}  // namespace

std::vector<Vec4f> ParseVertexCsv(std::string_view text, const std::string& file_name, Diagnostics& diagnostics,
                                  std::string_view columns) {
  std::vector<Vec4f> rows;
  std::vector<std::string_view> lines = SplitLines(text);
  // The separator: ';' when the first non-empty line holds one, otherwise ',' (blanks and tabs
  // separate in both). A ';' file often writes decimal commas, which are refused, not misread.
  char separator = ',';
  for (std::string_view line : lines) {
    if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
    if (line.find(';') != std::string_view::npos) separator = ';';
    break;
  }
  const char other = separator == ';' ? ',' : ';';
  std::vector<std::string> header;
  std::optional<ColumnChoice> choice;
  bool first_row = true;
  RowErrors errors(file_name, diagnostics);
  for (std::size_t n = 0; n < lines.size(); ++n) {
    const int line_number = static_cast<int>(n) + 1;
    if (std::size_t at = lines[n].find(other); at != std::string_view::npos) {
      errors.Add(line_number, static_cast<int>(at) + 1, DiagnosticCode::kCsvSeparator,
                 separator == ';' ? "',' in a ';'-separated file: write decimals with '.' (1.5, not 1,5)"
                                  : "';' in a ','-separated file: separate every row the same way");
      continue;
    }
    std::vector<Cell> cells = SplitCells(lines[n], separator);
    if (cells.empty()) continue;
    std::vector<float> values(cells.size());
    std::vector<NumberError> cell_errors(cells.size());
    int numbers = 0;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      cell_errors[c] = ParseNumber(cells[c].text, values[c]);
      numbers += cell_errors[c] == NumberError::kNone;
    }
    if (first_row) {
      first_row = false;
      if (numbers == 0) {  // a header: names only
        for (const Cell& cell : cells) header.emplace_back(cell.text);
        if (!columns.empty()) {
          Result<ColumnChoice> chosen = ChooseColumns(header, columns);
          if (!chosen) {
            diagnostics.Error({file_name, line_number, 1}, chosen.error().code, chosen.message());
            return {};
          }
          choice = std::move(chosen).value();
        }
        continue;
      }
      if (!columns.empty()) {
        diagnostics.Error({file_name, line_number, 1}, DiagnosticCode::kCsvColumns,
                          fmt::format("columns '{}' asked for, but the first row is numbers, not a header naming "
                                      "the columns",
                                      columns));
        return {};
      }
    }
    // The cells this row gives the vertex: the chosen columns, or all of them (at most four).
    std::vector<std::pair<std::size_t, int>> wanted;
    if (choice) {
      wanted = choice->cell_to_lane;
    } else {
      for (std::size_t c = 0; c < cells.size(); ++c) wanted.emplace_back(c, static_cast<int>(c));
    }
    Vec4f row = kDefaultInput;
    const RowCells row_cells{cells, values, cell_errors};
    if (std::optional<RowProblem> problem = FillVertex(row_cells, wanted, header, lines[n].size(), row)) {
      errors.Add(line_number, problem->column, problem->code, std::move(problem->message));
    } else {
      rows.push_back(row);
    }
  }
  return rows;
}

Result<InputSpec> ParseInputSpec(std::string_view flag) {
  std::size_t equals = flag.find('=');
  if (equals == std::string_view::npos) {
    return Failure(DiagnosticCode::kInputFlag, fmt::format("'{}': expected v#=FILE.csv or v#=FILE.csv:COLUMNS", flag));
  }
  std::string_view name = flag.substr(0, equals);
  const int index = ParseInputRegister(name).value_or(-1);
  if (index < 0 || index >= kInputRegisterCount) {
    return Failure(DiagnosticCode::kInputFlag, fmt::format("'{}' is not an input register v0-v15", name));
  }
  InputSpec spec{index, std::string(flag.substr(equals + 1)), ""};
  // FILE:COLUMNS, unless the whole text names a file (a path may hold ':').
  std::size_t colon = spec.file.rfind(':');
  std::error_code ignored;
  if (colon != std::string::npos && !std::filesystem::exists(spec.file, ignored)) {
    spec.columns = spec.file.substr(colon + 1);
    spec.file.resize(colon);
  }
  return spec;
}

namespace {

// "c0, c2, c3" of the registers {0, 2, 3} with letter 'c'.
std::string RegisterNames(char letter, const std::vector<int>& registers) {
  std::vector<std::string> out;
  for (int r : registers) out.push_back(fmt::format("{}{}", letter, r));
  return fmt::format("{}", fmt::join(out, ", "));
}

}  // namespace

UnsetRegisters FindUnsetRegisters(const Program& program, const std::vector<int>& constants_given,
                                  const std::vector<int>& inputs_given) {
  UnsetRegisters out = FindUnsetRegisters(program, AssignedConstants{constants_given, {}, {}}, inputs_given);
  out.integers.clear();
  out.booleans.clear();
  return out;
}

UnsetRegisters FindUnsetRegisters(const Program& program, const AssignedConstants& constants_given,
                                  const std::vector<int>& inputs_given) {
  std::set<int> defined, constants_read, inputs_read, integers_read, booleans_read, integers_defined, booleans_defined;
  bool relative = false;  // a0.x-relative reads: any constant may be read
  for (const Instruction& instruction : program.instructions) {
    const OpcodeInfo& info = instruction.info();
    if (instruction.opcode == Opcode::kDef) defined.insert(instruction.dest.reg.index);
    if (instruction.opcode == Opcode::kDefi) integers_defined.insert(instruction.dest.reg.index);
    if (instruction.opcode == Opcode::kDefb) booleans_defined.insert(instruction.dest.reg.index);
    if (!info.is_executable()) continue;
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      const int rows = info.registers_read(s);
      relative = relative || (reg.file == RegisterFile::kConst && reg.relative);
      for (int row = 0; row < rows; ++row) {
        if (reg.file == RegisterFile::kConst && !reg.relative) constants_read.insert(reg.index + row);
        if (reg.file == RegisterFile::kInput) inputs_read.insert(reg.index + row);
      }
      if (reg.file == RegisterFile::kConstInt) integers_read.insert(reg.index);
      if (reg.file == RegisterFile::kConstBool) booleans_read.insert(reg.index);
    }
  }
  const std::set<int> given(constants_given.floats.begin(), constants_given.floats.end());
  UnsetRegisters out;
  // i#/b# read that neither a defi/defb (definitions apply before the program runs) nor the caller sets.
  auto unset_flow = [](const std::set<int>& read, const std::set<int>& defined_here, const std::vector<int>& given_here,
                       std::vector<int>& unset, std::vector<int>& overridden) {
    for (int r : read) {
      if (!defined_here.contains(r) && std::find(given_here.begin(), given_here.end(), r) == given_here.end()) unset.push_back(r);
    }
    for (int r : std::set<int>(given_here.begin(), given_here.end())) {
      if (defined_here.contains(r)) overridden.push_back(r);
    }
  };
  unset_flow(integers_read, integers_defined, constants_given.integers, out.integers, out.integers_overridden);
  unset_flow(booleans_read, booleans_defined, constants_given.booleans, out.booleans, out.booleans_overridden);
  for (int c : constants_read) {
    if (!defined.contains(c) && !given.contains(c)) out.constants.push_back(c);
  }
  for (int c : given) {
    if (defined.contains(c)) out.overridden.push_back(c);
    if (!relative && !constants_read.contains(c) && !defined.contains(c)) out.unread.push_back(c);
  }
  for (int v : inputs_read) {
    if (std::find(inputs_given.begin(), inputs_given.end(), v) == inputs_given.end()) out.inputs.push_back(v);
  }
  return out;
}

Status CheckNoUnsetRegisters(const UnsetRegisters& unset, const std::vector<int>& inputs_given,
                             const RegisterSources& sources) {
  if (unset.constants.empty() && unset.inputs.empty() && unset.integers.empty() && unset.booleans.empty()) return {};
  std::vector<std::string> problems;
  if (!unset.constants.empty()) {
    problems.push_back(fmt::format("the program reads {}, which neither {} sets", RegisterNames('c', unset.constants),
                                   sources.constants));
    if (!unset.unread.empty()) problems.back() += fmt::format(" (they set {}, which it never reads)", RegisterNames('c', unset.unread));
  }
  for (const auto& [letter, registers] : {std::pair{'i', &unset.integers}, std::pair{'b', &unset.booleans}}) {
    if (!registers->empty()) {
      problems.push_back(fmt::format("the program reads {}, which neither {} sets", RegisterNames(letter, *registers),
                                     sources.constants));
    }
  }
  if (!unset.inputs.empty()) {
    problems.push_back(fmt::format("the program reads {}, which no {} supplies", RegisterNames('v', unset.inputs), sources.inputs));
    if (!inputs_given.empty()) problems.back() += fmt::format(" (given: {})", RegisterNames('v', inputs_given));
  }
  return Failure(DiagnosticCode::kUnsetRegister, fmt::format("{}; pass {} to run with them as 0 (inputs as 0, 0, 0, 1)",
                                                             fmt::join(problems, "; "), sources.allow));
}

std::vector<std::string> UnsetRegisterWarnings(const Program& program, const std::vector<int>& constants_given,
                                               const std::vector<int>& inputs_given) {
  return UnsetRegisterWarnings(FindUnsetRegisters(program, constants_given, inputs_given));
}

std::vector<std::string> UnsetRegisterWarnings(const UnsetRegisters& registers) {
  const std::vector<int>& unset = registers.constants;
  const std::vector<int>& overridden = registers.overridden;
  const std::vector<int>& missing = registers.inputs;
  std::vector<std::string> warnings;
  if (!unset.empty()) {
    warnings.push_back(fmt::format("the program reads {}, which no def, --consts or --const sets: {} 0, 0, 0, 0",
                                   RegisterNames('c', unset), unset.size() == 1 ? "it reads" : "they read"));
  }
  if (!registers.integers.empty()) {
    warnings.push_back(fmt::format("the program reads {}, which no defi, --consts or --const sets: {} 0, 0, 0, 0 "
                                   "(a rep or loop over it runs no iteration)",
                                   RegisterNames('i', registers.integers), registers.integers.size() == 1 ? "it reads" : "they read"));
  }
  if (!registers.booleans.empty()) {
    warnings.push_back(fmt::format("the program reads {}, which no defb, --consts or --const sets: {} false",
                                   RegisterNames('b', registers.booleans), registers.booleans.size() == 1 ? "it reads" : "they read"));
  }
  if (!overridden.empty()) {
    warnings.push_back(fmt::format("the program's def of {} overrides the value given by --consts or --const "
                                   "(def lines win)",
                                   RegisterNames('c', overridden)));
  }
  for (const auto& [letter, list] : {std::pair{'i', &registers.integers_overridden}, std::pair{'b', &registers.booleans_overridden}}) {
    if (!list->empty()) {
      warnings.push_back(fmt::format("the program's def{} of {} overrides the value given by --consts or --const "
                                     "(def lines win)",
                                     letter, RegisterNames(letter, *list)));
    }
  }
  if (!missing.empty()) {
    warnings.push_back(fmt::format("the program reads {}, which no --input or --sphere supplies: {} 0, 0, 0, 1",
                                   RegisterNames('v', missing), missing.size() == 1 ? "it reads" : "they read"));
  }
  return warnings;
}

std::string FormatFloat(float value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);  // fmt prints the shortest round-trip form
}

void WriteOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix,
                    const std::function<void(std::string_view)>& write) {
  // Rows formatted per piece handed to `write`: 4096 rows of at most 80 cells of 16 characters.
  constexpr std::size_t kRowsPerPiece = 4096;
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
  std::string piece = fmt::format("{}\n", fmt::join(header, ","));
  const std::size_t prefix_width = prefix.header.size();
  for (std::size_t i = 0; i < outputs.count(); ++i) {
    const char* separator = "";
    if (prefix_width > 0 && (i + 1) * prefix_width <= prefix.values.size()) {
      for (std::size_t c = 0; c < prefix_width; ++c, separator = ",") {
        piece += separator;
        piece += FormatFloat(prefix.values[i * prefix_width + c]);
      }
    }
    for (auto [slot, lane] : columns) {
      piece += separator;
      piece += FormatFloat(outputs.lane(slot, lane)[i]);
      separator = ",";
    }
    piece += '\n';
    if ((i + 1) % kRowsPerPiece == 0) {
      write(piece);
      piece.clear();
    }
  }
  write(piece);
}

std::string FormatOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix) {
  std::string out;
  WriteOutputCsv(program, outputs, prefix, [&out](std::string_view piece) { out += piece; });
  return out;
}

}  // namespace vs11
