#include "vm/cli/trace_output.h"

#include <cmath>
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

// JSON numbers cannot be NaN or infinite: those lanes are the strings "nan", "inf", "-inf".
json Vec4Json(const Vec4f& value) {
  json lanes = json::array();
  for (float v : value) {
    if (std::isnan(v)) {
      lanes.push_back("nan");
    } else if (std::isinf(v)) {
      lanes.push_back(v > 0 ? "inf" : "-inf");
    } else {
      lanes.push_back(static_cast<double>(v));  // exact: every float is a double
    }
  }
  return lanes;
}

std::string LaneLetters(WriteMask mask) {
  std::string letters;
  for (int lane = 0; lane < 4; ++lane) {
    if (mask.has(lane)) letters += kLaneLetters[lane];
  }
  return letters;
}

json TraceJson(const Program& program, const VertexTrace& trace, SourceLines& sources) {
  json vertex = {{"vertex", trace.vertex}, {"identical", trace.identical()}};
  json inputs = json::object();
  for (int reg : trace.input_registers) inputs[fmt::format("v{}", reg)] = Vec4Json(trace.start.inputs[reg]);
  vertex["inputs"] = inputs;
  json steps = json::array();
  for (const TraceStep& step : trace.steps) {
    const Instruction& instruction = program.instructions[step.instruction_index];
    SourceLoc loc = program.LocOf(step.instruction_index);
    json entry = {{"index", step.instruction_index}, {"instruction", FormatInstruction(instruction)}};
    if (!loc.file.empty()) {
      entry["file"] = loc.file;
      entry["line"] = loc.line;
      if (std::optional<std::string> line = sources.Line(loc)) entry["source"] = SourceStatement(*line);
    }
    json reads = json::array();
    for (const TracedRead& read : step.reads) {
      reads.push_back({{"operand", FormatSource(instruction.sources[read.source])},
                       {"source", read.source},
                       {"row", read.row},
                       {"register", RegisterName(read.register_read.file, read.register_read.index)},
                       {"raw", Vec4Json(read.raw)},
                       {"value", Vec4Json(read.value)}});
    }
    entry["reads"] = reads;
    if (step.write) {
      entry["write"] = {{"register", RegisterName(instruction.dest.reg.file, instruction.dest.reg.index)},
                        {"lanes", LaneLetters(step.write->written)},
                        {"before", Vec4Json(step.write->before)},
                        {"after", Vec4Json(step.write->after)}};
    }
    steps.push_back(entry);
  }
  vertex["steps"] = steps;
  json outputs = json::array();
  for (const TracedOutput& output : trace.outputs) {
    outputs.push_back({{"register", OutputSlotName(output.slot)},
                       {"reference", Vec4Json(output.reference)},
                       {"engine", Vec4Json(output.engine)},
                       {"identical", output.identical()}});
  }
  vertex["outputs"] = outputs;
  return vertex;
}

}  // namespace

void TraceFlags::AddTo(CLI::App& command) {
  CLI::Option* trace = command.add_option("--trace", vertices,
                     "Debug these vertices (0-based, comma-separated): every instruction with its source line, "
                     "the values read and the lanes written, on stdout")
      ->delimiter(',');
  command.add_option("--trace-json", json_file, "Also write the --trace record as JSON to this file")->needs(trace);
}

void ReportTraces(const TraceFlags& flags, const std::string& program_path, const Program& program,
                  const ConstantBank& constants, const VertexArrays& inputs, const VertexArrays& engine_outputs,
                  std::string_view engine_name) {
  for (std::size_t vertex : flags.vertices) {
    if (vertex >= inputs.count()) {
      Fail(fmt::format("--trace {}: there are {} vertices (0 to {})", vertex, inputs.count(), inputs.count() - 1));
    }
  }
  SourceLines sources;
  json document = {{"program", program_path}, {"engine", engine_name}};
  json vertices = json::array();
  std::vector<std::size_t> different;
  for (std::size_t vertex : flags.vertices) {
    VertexTrace trace = TraceVertex(program, constants, inputs, vertex);
    CompareOutputs(engine_outputs, trace);
    std::fputs(FormatTraceText(program, trace, engine_name, sources).c_str(), stdout);
    if (!trace.identical()) different.push_back(vertex);
    vertices.push_back(TraceJson(program, trace, sources));
  }
  document["vertices"] = vertices;
  document["identical"] = different.empty();
  if (!flags.json_file.empty()) {
    if (std::optional<std::string> error = WriteFileAtomically(flags.json_file, document.dump(2) + "\n")) Fail(*error);
  }
  if (!different.empty()) {
    std::fflush(stdout);
    Fail(fmt::format("the {} engine differs from the reference engine on vertex {}", engine_name,
                     fmt::join(different, ", ")));
  }
}

}  // namespace vs11::cli
