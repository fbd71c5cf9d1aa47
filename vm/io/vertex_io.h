// Text formats around a program run: constant files, --const flags, vertex CSV in and out.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/diagnostic.h"
#include "vm/core/machine.h"
#include "vm/core/result.h"

namespace vs11 {

// The registers a constants text set, by file, in the order its lines set them.
struct AssignedConstants {
  std::vector<int> floats;    // c#
  std::vector<int> integers;  // i#
  std::vector<int> booleans;  // b#
};

// Constant files hold one register per line, either as a def line (`def c12, 1, 0, 0, 1`) or as
// `c12 = 1 0 0 1` (commas optional). Blank lines and ; // # comments are skipped. Fewer than four
// values leave the rest 0. The later models' integer and boolean constants are written the same
// ways: `defi i0, 3, 0, 1, 0` or `i0 = 3 0 1 0` (integers: x the loop or rep count 0-255, y aL's
// first value 0-255, z aL's step -128-127, w 0, as D3D9's loop reads them), `defb b2, true` or
// `b2 = true` (true/false or 1/0). Errors carry file:line:column; values land in `bank`.
// `assigned`, when given, receives the index of every register a line set.
void ParseConstantsText(std::string_view text, const std::string& file_name, ConstantBank& bank,
                        Diagnostics& diagnostics, AssignedConstants* assigned = nullptr);

// `c4=1,0,0,1`, `i0=3,0,1` or `b2=true` (the --const flag). The error is the first problem
// ParseConstantsText finds, its message ending "in 'TEXT'", its place "--const:1:COLUMN".
Status ParseConstantAssignment(std::string_view text, ConstantBank& bank, AssignedConstants* assigned = nullptr);

// What a run should warn about before it starts, one message each: constant registers the program
// reads (by absolute address; matrix rows included) that neither a def nor `constants_given` set
// (they read 0), input registers it reads that are not in `inputs_given` (they read 0, 0, 0, 1), and
// registers in `constants_given` that a def of the program overrides (def lines win).
std::vector<std::string> UnsetRegisterWarnings(const Program& program, const std::vector<int>& constants_given,
                                               const std::vector<int>& inputs_given);

// The registers behind those warnings, each list ascending.
struct UnsetRegisters {
  std::vector<int> constants;   // read, set by neither a def nor constants_given
  std::vector<int> overridden;  // in constants_given, and defined by a def (which wins)
  std::vector<int> inputs;      // read, not in inputs_given
  std::vector<int> unread;      // in constants_given but never read (relative addressing aside)
  std::vector<int> integers;    // i# read (rep, loop), set by neither a defi nor the given ones
  std::vector<int> booleans;    // b# read (if, callnz), set by neither a defb nor the given ones
  std::vector<int> integers_overridden;  // given, and defined by a defi (which wins)
  std::vector<int> booleans_overridden;  // given, and defined by a defb (which wins)
};
// Checks c# and v# only: for callers that have no way to set i# and b#.
UnsetRegisters FindUnsetRegisters(const Program& program, const std::vector<int>& constants_given,
                                  const std::vector<int>& inputs_given);
// Checks i# and b# too (`vs11 run`, whose --const and --consts set them).
UnsetRegisters FindUnsetRegisters(const Program& program, const AssignedConstants& constants_given,
                                  const std::vector<int>& inputs_given);
// The warnings for registers already found (i# and b# included where they were looked for).
std::vector<std::string> UnsetRegisterWarnings(const UnsetRegisters& unset);

// How a caller names what sets registers, for CheckNoUnsetRegisters: `vs11 run`'s flags or Python's
// arguments.
struct RegisterSources {
  std::string_view constants;  // "a def, --consts or --const"
  std::string_view inputs;     // "--input or --sphere"
  std::string_view allow;      // how to run anyway: "--missing zeros"
};
// Why a run that refuses unset registers (the default: --missing error, missing='error') stops
// (kUnsetRegister), or success when the program reads nothing unset: "the program reads c4, which
// neither a def, --consts or --const sets (they set c44, which it never reads); ...; pass --missing
// zeros to ...".
Status CheckNoUnsetRegisters(const UnsetRegisters& unset, const std::vector<int>& inputs_given,
                             const RegisterSources& sources);

// Vertex CSV: one vertex a row. Cells are separated by ',' (or by ';' when the first row holds
// one; a ',' is then refused as a likely decimal comma), and by blanks or tabs in either. Numbers
// include inf, -inf and nan. A first row of names only is a header; a first row of numbers is data.
// Without `columns` each row holds 1 to 4 numbers, missing components filled from kDefaultInput
// (0, 0, 0, 1). `columns` picks cells by header name: "oPos" takes oPos.x..oPos.w into their lanes
// (as `vs11 run` writes them), "a,b,c" (or one "name.x") fills lanes x, y, z... in that order.
// Errors carry file:line:column; of many bad rows only the first is reported, with the count.
std::vector<Vec4f> ParseVertexCsv(std::string_view text, const std::string& file_name, Diagnostics& diagnostics,
                                  std::string_view columns = {});

// The --input flag: "v1=FILE.csv" or "v1=FILE.csv:COLUMNS" (see ParseVertexCsv; a FILE that
// exists as written, ':' and all, is taken whole). An error (kInputFlag) when malformed.
struct InputSpec {
  int reg = 0;
  std::string file;
  std::string columns;
};
Result<InputSpec> ParseInputSpec(std::string_view flag);

// Formats the written output lanes as CSV with a header `oPos.x,...,oD0.z`. `prefix` columns (header,
// then header.size() values per row, row after row) come first when given.
struct CsvColumns {
  std::vector<std::string> header;
  std::vector<float> values;
};
std::string FormatOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix = {});
// The same text handed to `write` a few hundred KB at a time, for output of any size.
void WriteOutputCsv(const Program& program, const VertexArrays& outputs, const CsvColumns& prefix,
                    const std::function<void(std::string_view)>& write);

// Shortest text that reads back as the same float.
std::string FormatFloat(float value);

}  // namespace vs11
