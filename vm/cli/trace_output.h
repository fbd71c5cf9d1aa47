// `vs11 run --trace V[,V...] [--trace-json FILE]`: the shader debugger's flags and output (vm/engines/trace.h).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "vm/core/machine.h"

namespace vs11::cli {

struct TraceFlags {
  std::vector<std::size_t> vertices;
  std::string json_file;

  void AddTo(CLI::App& command);
  bool active() const { return !vertices.empty(); }
};

// Traces each chosen vertex on the reference engine under `rules`, prints the traces to stdout, writes the JSON
// file (atomically) when asked, and compares with `engine_outputs` (the run of `engine_name` over the
// same inputs): any difference fails the command (exit 1) after the traces are printed.
void ReportTraces(const TraceFlags& flags, const std::string& program_path, const Program& program,
                  const ConstantBank& constants, const VertexArrays& inputs, const VertexArrays& engine_outputs,
                  std::string_view engine_name, FloatRules rules);

}  // namespace vs11::cli
