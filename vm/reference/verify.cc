// Program verification against references, and engine-against-engine comparison. See verify.h.
#include "vm/reference/verify.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

std::string LaneLetters(WriteMask mask) {
  std::string letters;
  for (int lane = 0; lane < 4; ++lane) {
    if (mask.has(lane)) letters += kLaneLetters[lane];
  }
  return letters;
}

// Registers a program reads, to give them random values.
std::vector<int> InputRegistersRead(const Program& program) {
  std::vector<int> registers;
  for (const Instruction& instruction : program.instructions) {
    const OpcodeInfo& info = instruction.info();
    if (instruction.opcode == Opcode::kDcl) registers.push_back(instruction.dest.reg.index);
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file == RegisterFile::kInput) registers.push_back(reg.index);
    }
  }
  std::sort(registers.begin(), registers.end());
  registers.erase(std::unique(registers.begin(), registers.end()), registers.end());
  std::erase_if(registers, [](int reg) { return reg < 0 || reg >= kInputRegisterCount; });
  return registers;
}

// Inputs and constants for VerifyEngines when no reference is named: SplitMix64, like the references.
struct RandomCase {
  ConstantBank constants;
  VertexArrays inputs;
};
RandomCase MakeRandomCase(const Program& program, const VerifyOptions& options) {
  std::uint64_t state = options.seed;
  auto uniform = [&state](double lo, double hi) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<float>(lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1p-53);
  };
  constexpr double kRange = 2.0;
  RandomCase rc{ConstantBank(options.constant_count), {}};
  for (int i = 0; i < rc.constants.size(); ++i) {
    for (float& v : rc.constants[i]) v = uniform(-kRange, kRange);
  }
  const std::vector<int> registers = InputRegistersRead(program);
  const std::size_t count = static_cast<std::size_t>(std::max(options.samples, 1));
  rc.inputs = MakeInputArrays(count, registers);
  for (int reg : registers) {
    for (int c = 0; c < 4; ++c) {
      float* lane = rc.inputs.lane(reg, c);
      for (std::size_t i = 0; i < count; ++i) lane[i] = uniform(-kRange, kRange);
    }
  }
  return rc;
}

std::string FormatVec(const Vec4f& v) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g}, {:.9g})", v[0], v[1], v[2], v[3]);
}
// Lanes outside `lanes` (not compared) print as "-".
std::string FormatVec(const glm::dvec4& v, WriteMask lanes) {
  std::array<std::string, 4> parts;
  for (int lane = 0; lane < 4; ++lane) parts[lane] = lanes.has(lane) ? fmt::format("{:.9g}", v[lane]) : "-";
  return fmt::format("({}, {}, {}, {})", parts[0], parts[1], parts[2], parts[3]);
}

}  // namespace

// ---- Verify ---------------------------------------------------------------------------------------

std::string OutputReport::Name() const { return fmt::format("{}.{}", OutputSlotName(slot), LaneLetters(lanes)); }

namespace {

// One expected output against what the engine wrote (`written`: the lanes the program writes of
// that slot; unwritten slots read as the machine's initial output values).
OutputReport CompareOutput(const ExpectedOutput& expected, const VertexArrays& outputs, WriteMask written,
                           const ReferenceCase& rc, std::optional<double> tolerance) {
  const std::size_t count = rc.inputs.count();
  OutputReport out;
  out.slot = expected.slot;
  out.lanes = expected.lanes;
  out.tolerance = tolerance.value_or(expected.tolerance);
  out.missing_lanes = WriteMask(static_cast<std::uint8_t>(expected.lanes.bits() & ~written.bits()));
  for (const glm::dvec4& v : expected.values) {
    for (int lane = 0; lane < 4; ++lane) {
      if (expected.lanes.has(lane)) out.scale = std::max(out.scale, std::abs(v[lane]));
    }
  }
  const double scale = out.scale > 0 ? out.scale : 1.0;
  double sum_squares = 0.0;
  std::size_t lanes_counted = 0;
  double worst = -1.0;
  for (std::size_t i = 0; i < count; ++i) {
    for (int lane = 0; lane < 4; ++lane) {
      if (!expected.lanes.has(lane)) continue;
      const double actual = outputs.has(expected.slot) ? outputs.lane(expected.slot, lane)[i]
                                                       : UnwrittenOutputValue(expected.slot)[lane];
      double error_abs = std::abs(actual - expected.values[i][lane]);
      if (std::isnan(error_abs)) error_abs = std::numeric_limits<double>::infinity();
      sum_squares += error_abs * error_abs;
      ++lanes_counted;
      if (error_abs > worst) {
        worst = error_abs;
        out.worst_vertex = i;
        out.worst_lane = lane;
      }
    }
  }
  out.max_absolute = std::max(worst, 0.0);
  out.rms_absolute = lanes_counted ? std::sqrt(sum_squares / static_cast<double>(lanes_counted)) : 0.0;
  out.max_relative = out.max_absolute / scale;
  out.rms_relative = out.rms_absolute / scale;
  out.expected = expected.values.empty() ? glm::dvec4(0.0) : expected.values[out.worst_vertex];
  for (int lane = 0; lane < 4; ++lane) {
    out.actual[lane] = outputs.has(expected.slot) && count > 0 ? outputs.lane(expected.slot, lane)[out.worst_vertex]
                                                               : UnwrittenOutputValue(expected.slot)[lane];
  }
  for (const NamedInput& input : rc.named_inputs) {
    InputValue value{input.name, input.reg, {}};
    for (int c = 0; c < 4 && count > 0; ++c) value.value[c] = rc.inputs.lane(input.reg, c)[out.worst_vertex];
    out.worst_inputs.push_back(value);
  }
  out.pass = out.missing_lanes.bits() == 0 && out.max_relative <= out.tolerance;
  return out;
}

}  // namespace

VerifyReport Verify(const Program& program, const ProgramMetadata& metadata, const VerifyOptions& options) {
  VerifyReport report;
  report.reference = metadata.reference;
  report.engine = options.engine;
  report.seed = options.seed;
  if (metadata.reference.empty()) {
    report.error = "no reference named: add a '; vs11: reference=NAME' line to the program or pass --reference NAME "
                   "(known: " + ReferenceNames() + ")";
    return report;
  }
  const ReferenceInfo* info = FindReference(metadata.reference);
  if (!info) {
    report.error = fmt::format("unknown reference '{}' (known: {})", metadata.reference, ReferenceNames());
    return report;
  }
  ReferenceOptions reference_options;
  reference_options.coefficients = options.coefficients.value_or(RandomCoefficients(options.seed));
  reference_options.samples = options.samples;
  reference_options.seed = options.seed;
  reference_options.constant_count = options.constant_count;
  Result<ReferenceCase> rc = info->build(metadata, reference_options);
  if (!rc) {
    report.error = fmt::format("reference '{}': {}", metadata.reference, rc.message());
    return report;
  }
  report.description = rc->description;
  const std::size_t count = rc->inputs.count();
  report.vertices = count;

  Result<std::unique_ptr<Engine>> engine = MakeEngine(options.engine, program, rc->constants, options.engine_options);
  if (!engine) {
    report.error = engine.message();
    return report;
  }
  VertexArrays outputs = MakeOutputArrays(count, program);
  if (const Status ran = (*engine)->Run(rc->inputs, outputs); !ran) {
    report.error = ran.message();
    return report;
  }
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(program);

  report.pass = true;
  for (const ExpectedOutput& expected : rc->expected) {
    OutputReport out = CompareOutput(expected, outputs, written[expected.slot], *rc, options.tolerance);
    report.pass = report.pass && out.pass;
    report.outputs.push_back(std::move(out));
  }
  return report;
}

std::string FormatVerifyReport(const VerifyReport& report) {
  if (!report.error.empty()) return "error: " + report.error + "\n";
  std::string text = fmt::format("reference {}, engine {}, {} vertices, seed {}\n", report.description,
                                 report.engine, report.vertices, report.seed);
  for (const OutputReport& out : report.outputs) {
    text += fmt::format("  {:<9} max abs {:.3e}  rms abs {:.3e}  max rel {:.3e}  rms rel {:.3e}  (scale {:.6g})  "
                        "tolerance {:.1e}  {}\n",
                        out.Name(), out.max_absolute, out.rms_absolute, out.max_relative, out.rms_relative, out.scale,
                        out.tolerance, out.pass ? "PASS" : "FAIL");
    if (out.missing_lanes.bits() != 0) {
      text += fmt::format("            the program never writes {}.{}\n", OutputSlotName(out.slot),
                          LaneLetters(out.missing_lanes));
    }
  }
  if (!report.outputs.empty()) {
    const OutputReport& primary = report.outputs.front();
    for (const InputValue& input : primary.worst_inputs) {
      text += fmt::format("  worst {} (v{}, vertex {}): {}\n", input.name, input.reg, primary.worst_vertex,
                          FormatVec(input.value));
    }
    const std::string where = fmt::format("{} at vertex {}", OutputSlotName(primary.slot), primary.worst_vertex);
    text += fmt::format("  expected {}: {}\n", where, FormatVec(primary.expected, primary.lanes));
    text += fmt::format("  got      {}: {}\n", where, FormatVec(primary.actual));
  }
  text += report.pass ? "PASS\n" : "FAIL\n";
  return text;
}

std::string VerifyReportJson(const VerifyReport& report) {
  nlohmann::json json;
  if (!report.error.empty()) {
    json["error"] = report.error;
    json["pass"] = false;
    return json.dump(2);
  }
  json["reference"] = report.reference;
  json["description"] = report.description;
  json["engine"] = std::string(report.engine);
  json["vertices"] = report.vertices;
  json["seed"] = report.seed;
  json["pass"] = report.pass;
  nlohmann::json outputs = nlohmann::json::array();
  for (const OutputReport& out : report.outputs) {
    nlohmann::json o;
    o["register"] = OutputSlotName(out.slot);
    o["lanes"] = LaneLetters(out.lanes);
    o["missing_lanes"] = LaneLetters(out.missing_lanes);
    o["scale"] = out.scale;
    o["max_abs"] = out.max_absolute;
    o["rms_abs"] = out.rms_absolute;
    o["max_rel"] = out.max_relative;
    o["rms_rel"] = out.rms_relative;
    o["tolerance"] = out.tolerance;
    o["pass"] = out.pass;
    o["worst_vertex"] = out.worst_vertex;
    o["worst_lane"] = std::string(1, kLaneLetters[out.worst_lane]);
    o["expected"] = {out.expected.x, out.expected.y, out.expected.z, out.expected.w};
    o["actual"] = out.actual;
    nlohmann::json inputs = nlohmann::json::object();
    for (const InputValue& input : out.worst_inputs) inputs[input.name] = input.value;
    o["worst_inputs"] = inputs;
    outputs.push_back(o);
  }
  json["outputs"] = outputs;
  return json.dump(2);
}

// ---- engines --------------------------------------------------------------------------------------

EngineComparison CompareOutputArrays(const VertexArrays& a, const VertexArrays& b) {
  assert(a.count() == b.count() && a.registers() == b.registers());
  EngineComparison comparison;
  const std::size_t count = a.count();
  comparison.vertices = count;
  for (int slot : a.registers()) {
    for (int lane = 0; lane < 4; ++lane) {
      const float* la = a.lane(slot, lane);
      const float* lb = b.lane(slot, lane);
      for (std::size_t i = 0; i < count; ++i) {
        ++comparison.lanes_compared;
        if (std::bit_cast<std::uint32_t>(la[i]) == std::bit_cast<std::uint32_t>(lb[i])) continue;
        ++comparison.differing_lanes;
        if (!comparison.first || i < comparison.first->vertex) {
          comparison.first = EngineDifference{i, slot, lane, la[i], lb[i]};
        }
      }
    }
  }
  return comparison;
}

EngineComparison CompareEngines(const Program& program, std::string a, std::string b, const ConstantBank& constants,
                                const VertexArrays& inputs, const EngineOptions& engine_options) {
  const std::size_t count = inputs.count();
  VertexArrays out_a = MakeOutputArrays(count, program);
  VertexArrays out_b = MakeOutputArrays(count, program);
  EngineComparison failed;
  failed.a = a;
  failed.b = b;
  for (auto [kind, outputs] : {std::pair{a, &out_a}, std::pair{b, &out_b}}) {
    Result<std::unique_ptr<Engine>> engine = MakeEngine(kind, program, constants, engine_options);
    if (!engine) {
      failed.error = engine.message();
      return failed;
    }
    if (const Status ran = (*engine)->Run(inputs, *outputs); !ran) {
      failed.error = ran.message();
      return failed;
    }
  }
  EngineComparison comparison = CompareOutputArrays(out_a, out_b);
  comparison.a = a;
  comparison.b = b;
  return comparison;
}

EngineComparison VerifyEngines(const Program& program, const ProgramMetadata& metadata, std::string a, std::string b,
                               const VerifyOptions& options) {
  if (metadata.reference.empty()) {
    RandomCase rc = MakeRandomCase(program, options);
    EngineComparison comparison = CompareEngines(program, a, b, rc.constants, rc.inputs, options.engine_options);
    comparison.inputs = fmt::format("random inputs and constants in [-2, 2], seed {}", options.seed);
    return comparison;
  }
  EngineComparison failed;
  failed.a = a;
  failed.b = b;
  const ReferenceInfo* info = FindReference(metadata.reference);
  if (!info) {
    failed.error = fmt::format("unknown reference '{}' (known: {})", metadata.reference, ReferenceNames());
    return failed;
  }
  ReferenceOptions reference_options;
  reference_options.coefficients = options.coefficients.value_or(RandomCoefficients(options.seed));
  reference_options.samples = options.samples;
  reference_options.seed = options.seed;
  reference_options.constant_count = options.constant_count;
  Result<ReferenceCase> rc = info->build(metadata, reference_options);
  if (!rc) {
    failed.error = fmt::format("reference '{}': {}", metadata.reference, rc.message());
    return failed;
  }
  EngineComparison comparison = CompareEngines(program, a, b, rc->constants, rc->inputs, options.engine_options);
  comparison.inputs = fmt::format("inputs of reference {}, seed {}", rc->description, options.seed);
  return comparison;
}

std::string FormatEngineComparison(const EngineComparison& c) {
  if (!c.error.empty()) return "error: " + c.error + "\n";
  std::string text = fmt::format("engines {} and {}, {} vertices, {}\n  {} of {} output lanes differ\n",
                                 c.a, c.b, c.vertices, c.inputs, c.differing_lanes,
                                 c.lanes_compared);
  if (c.first) {
    text += fmt::format("  first difference: vertex {}, {}.{}: {} {:.9g} (0x{:08X}), {} {:.9g} (0x{:08X})\n",
                        c.first->vertex, OutputSlotName(c.first->slot), kLaneLetters[c.first->lane], c.a,
                        c.first->a, std::bit_cast<std::uint32_t>(c.first->a), c.b, c.first->b,
                        std::bit_cast<std::uint32_t>(c.first->b));
  }
  text += c.identical() ? "IDENTICAL\n" : "DIFFERENT\n";
  return text;
}

std::string EngineComparisonJson(const EngineComparison& c) {
  nlohmann::json json;
  if (!c.error.empty()) {
    json["error"] = c.error;
    json["identical"] = false;
    return json.dump(2);
  }
  json["engine_a"] = std::string(c.a);
  json["engine_b"] = std::string(c.b);
  json["inputs"] = c.inputs;
  json["vertices"] = c.vertices;
  json["lanes_compared"] = c.lanes_compared;
  json["differing_lanes"] = c.differing_lanes;
  json["identical"] = c.identical();
  if (c.first) {
    json["first_difference"] = {{"vertex", c.first->vertex},
                                {"register", OutputSlotName(c.first->slot)},
                                {"lane", std::string(1, kLaneLetters[c.first->lane])},
                                {"a", c.first->a},
                                {"b", c.first->b},
                                {"a_bits", std::bit_cast<std::uint32_t>(c.first->a)},
                                {"b_bits", std::bit_cast<std::uint32_t>(c.first->b)}};
  }
  return json.dump(2);
}

}  // namespace vs11
