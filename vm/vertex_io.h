// Text formats around a program run: constant files, --const flags, vertex CSV in and out.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/diagnostic.h"
#include "vm/machine.h"

namespace vs11 {

// Constant files hold one register per line, either as a def line (`def c12, 1, 0, 0, 1`) or as
// `c12 = 1 0 0 1` (commas optional). Blank lines and ; // # comments are skipped. Fewer than four
// values leave the rest 0. Errors carry file:line:column; values land in `bank`.
void ParseConstantsText(std::string_view text, const std::string& file_name, ConstantBank& bank,
                        Diagnostics& diagnostics);

// `c4=1,0,0,1` (the --const flag). Returns an error message on failure.
std::optional<std::string> ParseConstantAssignment(std::string_view text, ConstantBank& bank);

// Rows of 1 to 4 numbers separated by commas (or blanks); a first line that is not numeric is a
// header and is skipped. Missing components fill from kDefaultInput (0, 0, 0, 1).
std::vector<Vec4f> ParseVertexCsv(std::string_view text, const std::string& file_name, Diagnostics& diagnostics);

// Formats the written output lanes as CSV with a header `oPos.x,...,oD0.z`. `prefix_columns` (header,
// per-row values) come first when given.
struct CsvColumns {
  std::vector<std::string> header;
  std::vector<std::vector<float>> rows;
};
std::string FormatOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix = {});

// Shortest text that reads back as the same float.
std::string FormatFloat(float value);

}  // namespace vs11
