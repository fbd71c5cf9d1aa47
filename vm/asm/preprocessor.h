// The C preprocessor pass that D3DX ran over .vsh text before assembling it: #define (object-like and
// function-like), #undef, #include, #if/#ifdef/#ifndef/#elif/#else/#endif with integer expressions,
// #line, #error, and removal of the three comment forms (; to end of line, // to end of line, /* */).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "vm/core/diagnostic.h"

namespace vs11 {

struct PreprocessOptions {
  std::vector<std::filesystem::path> include_dirs;            // -I, searched after the includer's folder
  std::vector<std::pair<std::string, std::string>> defines;   // -D NAME[=VALUE]; VALUE defaults to "1"
  int max_include_depth = 64;                                  // deeper nesting (or a cycle) is an error
  std::size_t max_output_bytes = std::size_t{64} << 20;        // bounds runaway macro growth
  // Distinct macro names a program may #define (-D included). Real programs define tens; the bound
  // keeps the macro table, and a hostile file's time, small.
  std::size_t max_macros = 65536;
};

// How many macros may expand into one another to produce one token (a chain of #defines each
// naming the next, or macros nested in macro arguments). Each expansion step carries the set of
// macros that produced it, so the cost of a chain grows with the square of its length; the bound
// keeps it linear in the input. D3DX's own headers nest a few levels.
inline constexpr std::size_t kMaxMacroNesting = 256;

// One line of preprocessed text and where each of its characters came from.
struct PreprocessedLine {
  std::string text;          // comments removed, macros expanded, no trailing newline
  std::string file;          // the file (or #line name) the line came from
  int line = 0;              // 1-based line in that file (after #line adjustment)
  std::vector<int> columns;  // columns[i] = 1-based source column of text[i]; a macro's expansion
                             // takes the column of the macro name that was expanded
};

struct PreprocessResult {
  std::vector<PreprocessedLine> lines;  // only lines with non-blank text are kept
  Diagnostics diagnostics;
};

// Reads a whole file; std::nullopt when it cannot be read. Tests pass an in-memory map instead.
using FileReader = std::function<std::optional<std::string>(const std::filesystem::path&)>;
std::optional<std::string> ReadFileFromDisk(const std::filesystem::path& path);

// Preprocesses `text`, which came from `file_name` (used for messages and for finding
// #include "..." files beside it). Never throws on bad input: problems become diagnostics.
PreprocessResult Preprocess(std::string_view text, const std::string& file_name,
                            const PreprocessOptions& options, const FileReader& reader = ReadFileFromDisk);

}  // namespace vs11
