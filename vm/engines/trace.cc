#include "vm/engines/trace.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/asm/disassembler.h"
#include "vm/asm/lexer.h"
#include "vm/asm/program_file.h"
#include "vm/core/input_file.h"
#include "vm/engines/flow_trace.h"
#include "vm/io/vertex_io.h"

namespace vs11 {
namespace {

// The value a destination register holds in `state` (a0 as its integer in lane x).
Vec4f DestinationValue(const RegisterRef& reg, const VertexState& state) {
  if (reg.file == RegisterFile::kTemp) return reg.index < kTempRegisterCount ? state.temps[reg.index] : Vec4f{};
  if (reg.file == RegisterFile::kAddress) return {static_cast<float>(state.a0), 0.0f, 0.0f, 0.0f};
  if (std::optional<int> slot = OutputSlotOf(reg)) return state.outputs[*slot];
  return {};
}

// Records each executed instruction's reads before it runs and its write after.
class TraceRecorder final : public InstructionObserver {
 public:
  TraceRecorder(const Program& program, const ConstantBank& constants, std::vector<TraceStep>& steps)
      : program_(program), constants_(constants), steps_(steps) {}

  void Before(int instruction_index, const VertexState& state) override {
    const Instruction& instruction = program_.instructions[instruction_index];
    const OpcodeInfo& info = instruction.info();
    if (!info.is_executable()) return;
    TraceStep step;
    step.instruction_index = instruction_index;
    for (int s = 0; s < info.source_count(); ++s) {
      const SourceOperand& source = instruction.sources[s];
      const int rows = info.registers_read(s);
      for (int row = 0; row < rows; ++row) {
        TracedRead read;
        read.source = s;
        read.row = row;
        read.register_read = source.reg;
        read.register_read.index += row + (source.reg.relative ? state.a0 : 0);
        read.register_read.relative = false;
        read.raw = ReadRegister(source.reg, row, constants_, state);
        read.value = FetchSource(source, row, constants_, state);
        step.reads.push_back(read);
      }
    }
    if (info.kind != ResultKind::kNoResult) {
      std::uint8_t reachable = static_cast<std::uint8_t>((1u << info.result_lanes()) - 1);
      step.write = TracedWrite{WriteMask(instruction.dest.mask.bits() & reachable),
                               DestinationValue(instruction.dest.reg, state), {}, WriteMask(0)};
    }
    steps_.push_back(std::move(step));
  }

  void After(int instruction_index, const VertexState& state) override {
    if (steps_.empty() || steps_.back().instruction_index != instruction_index || !steps_.back().write) return;
    steps_.back().write->after = DestinationValue(program_.instructions[instruction_index].dest.reg, state);
  }

 private:
  const Program& program_;
  const ConstantBank& constants_;
  std::vector<TraceStep>& steps_;
};

bool SameBits(const Vec4f& a, const Vec4f& b) {
  for (int lane = 0; lane < 4; ++lane) {
    if (std::bit_cast<std::uint32_t>(a[lane]) != std::bit_cast<std::uint32_t>(b[lane])) return false;
  }
  return true;
}

std::string Collapse(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

std::string FormatBool(float lane) { return lane != 0.0f ? "true" : "false"; }

// "(true, false, true, true)": p0's lanes, or a predicate's.
std::string FormatBools(const Vec4f& lanes) {
  return fmt::format("({}, {}, {}, {})", FormatBool(lanes[0]), FormatBool(lanes[1]), FormatBool(lanes[2]),
                     FormatBool(lanes[3]));
}

// "r1.x -> r1 = (0.5, kept 0, kept 0, kept 0)": the destination as written, then the whole register.
// Later models: a0's four lanes as integers, p0's as true/false, and "off 2" for a lane the predicate
// turned off.
std::string FormatWrite(const DestOperand& dest, const TracedWrite& write, ShaderModel model) {
  const RegisterRef& reg = dest.reg;
  if (reg.file == RegisterFile::kAddress && model == ShaderModel::kVs11) {
    return write.written.has(0) ? fmt::format("a0.x -> a0.x = {}", static_cast<int>(write.after[0])) : "a0 kept";
  }
  auto format_lane = [&](float value) {
    if (reg.file == RegisterFile::kPredicate) return FormatBool(value);
    if (reg.file == RegisterFile::kAddress) return fmt::format("{}", static_cast<int>(value));
    return FormatFloat(value);
  };
  std::string lanes;
  for (int lane = 0; lane < 4; ++lane) {
    if (lane > 0) lanes += ", ";
    if (write.written.has(lane)) {
      lanes += format_lane(write.after[lane]);
    } else {
      lanes += (write.predicated_off.has(lane) ? "off " : "kept ") + format_lane(write.before[lane]);
    }
  }
  return fmt::format("{} -> {} = ({})", FormatDest(dest, model), RegisterName(reg.file, reg.index, model), lanes);
}

// "        read  r0.x = (...)   from r0 = (...)" for one read.
std::string FormatRead(const Instruction& instruction, const TracedRead& read, ShaderModel model) {
  if (read.source == TracedRead::kPredicateOperand) {  // (!p0.x) add ...: on or off per lane
    return fmt::format("        read  ({}) = {}   from p0 = {}\n", FormatSource(instruction.predicate, Syntax::kDx9, model),
                       FormatBools(read.value), FormatBools(read.raw));
  }
  const SourceOperand& source = instruction.sources[read.source];
  std::string operand = read.row == 0 ? FormatSource(source, Syntax::kDx9, model)
                                      : fmt::format("{} row {}", FormatSource(source, Syntax::kDx9, model), read.row);
  if (read.boolean) {
    std::string out = fmt::format("        read  {} = {}", operand, FormatBool(read.value[0]));
    if (source.reg.file == RegisterFile::kPredicate) out += fmt::format("   from p0 = {}", FormatBools(read.raw));
    return out + "\n";
  }
  std::string out = fmt::format("        read  {} = {}", operand, FormatVec4(read.value));
  // A plain read is its register; otherwise name the register and show it as stored.
  if (source.negate || !source.swizzle.is_identity() || source.reg.relative || read.row > 0 || source.absolute) {
    out += fmt::format("   from {} = {}", RegisterName(read.register_read.file, read.register_read.index, model),
                       FormatVec4(read.raw));
  }
  if (!read.address.empty()) out += fmt::format(" ({})", read.address);
  return out + "\n";
}

}  // namespace

bool TracedOutput::identical() const { return SameBits(reference, engine); }

bool VertexTrace::identical() const {
  return std::all_of(outputs.begin(), outputs.end(), [](const TracedOutput& output) { return output.identical(); });
}

VertexTrace TraceVertex(const Program& program, const ConstantBank& api_constants, const VertexArrays& inputs,
                        std::size_t vertex, FloatRules rules) {
  if (program.model() != ShaderModel::kVs11) return TraceFlowVertex(program, api_constants, inputs, vertex, rules);
  VertexTrace trace;
  trace.vertex = vertex;
  trace.input_registers = inputs.registers();
  std::sort(trace.input_registers.begin(), trace.input_registers.end());
  ConstantBank constants = ApplyDefinitions(program, api_constants);
  StartVertex(inputs, vertex, WrittenOutputLanes(program), trace.start);
  trace.end = trace.start;
  TraceRecorder recorder(program, constants, trace.steps);
  RunVertex(program, constants, trace.end, &recorder, rules);
  return trace;
}

void CompareOutputs(const VertexArrays& engine_outputs, VertexTrace& trace) {
  trace.outputs.clear();
  std::vector<int> slots = engine_outputs.registers();
  std::sort(slots.begin(), slots.end());
  for (int slot : slots) {
    TracedOutput output;
    output.slot = slot;
    output.reference = trace.end.outputs[slot];
    for (int c = 0; c < 4; ++c) output.engine[c] = engine_outputs.lane(slot, c)[trace.vertex];
    trace.outputs.push_back(output);
  }
}

std::optional<std::string> SourceLines::Line(const SourceLoc& loc) {
  if (loc.file.empty() || loc.line <= 0) return std::nullopt;
  auto [it, inserted] = files_.try_emplace(loc.file);
  if (inserted) {
    // Only a regular file can be read again: a pipe's program (/dev/stdin) is gone once assembled.
    std::optional<std::string> text;
    if (InputFileProblem(loc.file, /*pipes_allowed=*/false).ok()) text = ReadWholeFile(loc.file);
    if (text) {
      std::vector<std::string> lines;
      std::size_t start = 0;
      while (start <= text->size()) {
        std::size_t end = text->find('\n', start);
        if (end == std::string::npos) end = text->size();
        std::string line = text->substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(std::move(line));
        start = end + 1;
      }
      it->second = std::move(lines);
    }
  }
  if (!it->second || loc.line > static_cast<int>(it->second->size())) return std::nullopt;
  return (*it->second)[static_cast<std::size_t>(loc.line - 1)];
}

std::string SourceStatement(std::string_view line) {
  std::size_t comment = std::min(line.find(';'), line.find("//"));
  std::string_view statement = line.substr(0, comment);
  std::size_t first = statement.find_first_not_of(" \t");
  if (first == std::string_view::npos) return "";
  std::size_t last = statement.find_last_not_of(" \t");
  return std::string(statement.substr(first, last - first + 1));
}

std::string FormatVec4(const Vec4f& value) {
  return fmt::format("({}, {}, {}, {})", FormatFloat(value[0]), FormatFloat(value[1]), FormatFloat(value[2]),
                     FormatFloat(value[3]));
}

std::string FormatTraceText(const Program& program, const VertexTrace& trace, std::string_view engine_name,
                            SourceLines& sources) {
  std::string out = fmt::format("vertex {}\n", trace.vertex);
  for (int reg : trace.input_registers) {
    out += fmt::format("  input v{} = {}\n", reg, FormatVec4(trace.start.inputs[reg]));
  }
  int step_number = 0;
  for (const TraceStep& step : trace.steps) {
    const Instruction& instruction = program.instructions[step.instruction_index];
    std::string disassembly = FormatInstruction(instruction, Syntax::kDx9, program.model());
    SourceLoc loc = program.LocOf(step.instruction_index);
    std::optional<std::string> line = sources.Line(loc);
    ++step_number;
    if (line) {
      std::string statement = SourceStatement(*line);
      out += fmt::format("  [{}] {}:{}  {}\n", step_number, loc.file, loc.line, statement);
      if (Collapse(statement) != Collapse(disassembly)) out += fmt::format("        = {}\n", disassembly);
    } else if (!loc.file.empty()) {
      out += fmt::format("  [{}] {}:{}  {}\n", step_number, loc.file, loc.line, disassembly);
    } else {
      out += fmt::format("  [{}] instruction {}  {}\n", step_number, step.instruction_index, disassembly);
    }
    for (const TracedRead& read : step.reads) out += FormatRead(instruction, read, program.model());
    if (step.write) out += fmt::format("        write {}\n", FormatWrite(instruction.dest, *step.write, program.model()));
    if (!step.note.empty()) out += fmt::format("        flow  {}\n", step.note);
  }
  out += fmt::format("  outputs: reference | {}\n", engine_name);
  for (const TracedOutput& output : trace.outputs) {
    out += fmt::format("    {} = {} | {}  {}\n", OutputSlotName(output.slot), FormatVec4(output.reference),
                       FormatVec4(output.engine), output.identical() ? "identical" : "DIFFERENT");
  }
  return out;
}

// ---- JSON (vs11 run --trace-json, Program.trace in Python) ----

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

json BoolsJson(const Vec4f& lanes) {
  json out = json::array();
  for (float lane : lanes) out.push_back(lane != 0.0f);
  return out;
}

json ReadJson(const Instruction& instruction, const TracedRead& read, ShaderModel model) {
  if (read.source == TracedRead::kPredicateOperand) {
    return {{"operand", fmt::format("({})", FormatSource(instruction.predicate, Syntax::kDx9, model))},
            {"source", read.source},
            {"row", 0},
            {"register", "p0"},
            {"raw", BoolsJson(read.raw)},
            {"value", BoolsJson(read.value)}};
  }
  json out = {{"operand", FormatSource(instruction.sources[read.source], Syntax::kDx9, model)},
              {"source", read.source},
              {"row", read.row},
              {"register", RegisterName(read.register_read.file, read.register_read.index, model)}};
  if (read.boolean) {
    out["raw"] = BoolsJson(read.raw);
    out["value"] = read.value[0] != 0.0f;
  } else {
    out["raw"] = Vec4Json(read.raw);
    out["value"] = Vec4Json(read.value);
  }
  if (!read.address.empty()) out["address"] = read.address;
  return out;
}

}  // namespace

std::string TraceJson(const Program& program, const VertexTrace& trace, SourceLines& sources) {
  json vertex = {{"vertex", trace.vertex}, {"identical", trace.identical()}};
  json inputs = json::object();
  for (int reg : trace.input_registers) inputs[fmt::format("v{}", reg)] = Vec4Json(trace.start.inputs[reg]);
  vertex["inputs"] = inputs;
  json steps = json::array();
  for (const TraceStep& step : trace.steps) {
    const Instruction& instruction = program.instructions[step.instruction_index];
    SourceLoc loc = program.LocOf(step.instruction_index);
    json entry = {{"index", step.instruction_index},
                  {"instruction", FormatInstruction(instruction, Syntax::kDx9, program.model())}};
    if (!loc.file.empty()) {
      entry["file"] = loc.file;
      entry["line"] = loc.line;
      if (std::optional<std::string> line = sources.Line(loc)) entry["source"] = SourceStatement(*line);
    }
    json reads = json::array();
    for (const TracedRead& read : step.reads) reads.push_back(ReadJson(instruction, read, program.model()));
    entry["reads"] = reads;
    if (step.write) {
      const RegisterRef& reg = instruction.dest.reg;
      entry["write"] = {{"register", RegisterName(reg.file, reg.index, program.model())},
                        {"lanes", LaneLetters(step.write->written)},
                        {"before", Vec4Json(step.write->before)},
                        {"after", Vec4Json(step.write->after)}};
      if (step.write->predicated_off.bits() != 0) entry["write"]["predicated_off"] = LaneLetters(step.write->predicated_off);
    }
    if (!step.note.empty()) entry["flow"] = step.note;
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
  return vertex.dump();
}

}  // namespace vs11
