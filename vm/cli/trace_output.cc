#include "vm/cli/trace_output.h"

#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/asm/disassembler.h"
#include "vm/asm/lexer.h"
#include "vm/asm/program_file.h"
#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/core/atomic_file.h"
#include "vm/engines/trace.h"

namespace vs11::cli {
namespace {

using nlohmann::json;

}  // namespace

void TraceFlags::AddTo(CLI::App& command) {
  CLI::Option* trace = command.add_option("--trace", vertices,
                     "Debug these vertices (0-based, comma-separated): every instruction with its source line, "
                     "the values read and the lanes written, on stdout")
      ->delimiter(',')
      ->check(SizeNumber());
  command.add_option("--trace-json", json_file, "Also write the --trace record as JSON to this file")->needs(trace);
}

void ReportTraces(const TraceFlags& flags, const std::string& program_path, const Program& program,
                  const ConstantBank& constants, const VertexArrays& inputs, const VertexArrays& engine_outputs,
                  std::string_view engine_name, FloatRules rules) {
  for (std::size_t vertex : flags.vertices) {
    if (vertex >= inputs.count()) {
      Fail(fmt::format("--trace {}: there are {} vertices (0 to {})", vertex, inputs.count(), inputs.count() - 1));
    }
  }
  SourceLines sources;
  json document = {{"program", program_path}, {"engine", engine_name}, {"float_rules", kFloatRulesNames.Name(rules)}};
  json vertices = json::array();
  std::vector<std::size_t> different;
  for (std::size_t vertex : flags.vertices) {
    VertexTrace trace = TraceVertex(program, constants, inputs, vertex, rules);
    CompareOutputs(engine_outputs, trace);
    std::fputs(FormatTraceText(program, trace, engine_name, sources).c_str(), stdout);
    if (!trace.identical()) different.push_back(vertex);
    vertices.push_back(json::parse(TraceJson(program, trace, sources)));
  }
  document["vertices"] = vertices;
  document["identical"] = different.empty();
  if (!flags.json_file.empty()) {
    if (const Status written = WriteFileAtomically(flags.json_file, document.dump(2) + "\n"); !written) {
      Fail(written.message());
    }
  }
  if (!different.empty()) {
    std::fflush(stdout);
    Fail(fmt::format("the {} engine differs from the reference engine on vertex {}", engine_name,
                     fmt::join(different, ", ")));
  }
}

}  // namespace vs11::cli
