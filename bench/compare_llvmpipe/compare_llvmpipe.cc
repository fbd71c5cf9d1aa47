// vs11 against Mesa's llvmpipe on the same vertex programs, inputs and constants, in one run.
//
// For each vertex count, every program of programs/ is built from its reference's inputs and
// constants (vm/reference/program_references.h) and run
//  * by llvmpipe, as its GLSL ES 3.00 translation (vm/translate, `vs11 translate --to glsles300
//    --clip d3d`), through transform feedback with the rasterizer discarded, once with
//    LP_NUM_THREADS=1 and once with Mesa's default thread count;
//  * by llvmpipe as the program's `passthrough` floor: the cheapest shader with the same inputs and
//    outputs, which fetches every attribute the program reads (in the same formats) and writes every
//    output it writes, with one copy or one add per input and no other arithmetic (PassthroughSource).
//    llvmpipe's time minus this is its shading alone;
//  * by vs11's jit and batch engines (one thread).
// The three hand-written GLSL translations of shaders.h (the paper's program, directional_light,
// skinning) run beside them as rows of their own, a cross-check of the translator's outputs and speed.
// Each llvmpipe setting runs in a child process (fork), since Mesa reads LP_NUM_THREADS once, when
// the display is initialised; the child sends its results back as JSON through a pipe.
//
// Times are ns per vertex, medians of --repetitions, each repetition at least 2^20 vertices (many
// draws or Run calls for the small counts), after one untimed warm-up repetition; a llvmpipe
// repetition ends with glFinish. --cpu-time measures the CPU time of the whole process instead of
// wall time. The four workloads of a program take turns, one repetition each per round; the shading
// alone is the median of the rounds' (llvmpipe - passthrough). llvmpipe's outputs are read back once
// per program and compared with vs11's jit outputs: the largest |difference| / max(1, |vs11|) over
// every output lane must stay within --tolerance.

#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/bench_common.h"
#include "bench/compare_llvmpipe/shaders.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"
#include "vm/gl/gl_runner.h"
#include "vm/reference/program_references.h"
#include "vm/reference/verify.h"
#include "vm/translate/shader_graph.h"
#include "vm/translate/translate.h"

namespace vs11::bench::llvmpipe {
namespace {

using nlohmann::json;
using gl::CreateLlvmpipeContext;
using gl::GlAttribute;
using gl::TransformFeedbackRun;

constexpr int kUsageError = 2;
constexpr std::size_t kVerticesPerRepetition = std::size_t{1} << 20;

// An input register as a GL attribute at `location`: its first `components` lanes (GL supplies the
// rest as (0, 0, 0, 1), the lanes vs11 gets as uniform).
struct InputBinding {
  int reg;
  int location;
  int components;
};

// An output register as a transform-feedback varying: its first `components` lanes.
struct OutputBinding {
  OutputSlot slot;
  int components;
  std::string varying;
};

// A hand-written translation of shaders.h: its bindings are the shader's own.
struct HandWritten {
  const char* body;
  int constant_count;
  std::vector<InputBinding> inputs;
  std::vector<OutputBinding> outputs;
};

// One row of the report: a program of programs/, run by llvmpipe as the translator's GLSL or as a
// hand-written one.
struct Workload {
  std::string name;
  std::string file;  // in programs/
  std::optional<HandWritten> hand_written;
  double goal;  // vs11's jit must be this many times faster than llvmpipe's shading alone (issue #23)
};

// Issue #23's goals: the jit at least 1.5x llvmpipe's shading alone on every program, 4x on the paper's.
constexpr double kGoal = 1.5;
constexpr double kPaperGoal = 4.0;
constexpr char kPaperProgram[] = "sh9_irradiance.vsh";

std::vector<Workload> Workloads() {
  std::vector<Workload> workloads;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(ProgramsFolder())) {
    if (entry.path().extension() == ".vsh") files.push_back(entry.path().filename());
  }
  std::sort(files.begin(), files.end());
  for (const std::filesystem::path& file : files) {
    workloads.push_back({file.stem().string(), file.string(), std::nullopt, file == kPaperProgram ? kPaperGoal : kGoal});
  }
  const OutputSlot position = OutputSlot::kPosition, diffuse = OutputSlot::kDiffuse, specular = OutputSlot::kSpecular;
  workloads.push_back({"sh9_irradiance (hand GLSL)", kPaperProgram,
                       HandWritten{kSh9IrradianceBody, 7, {{0, 0, 3}}, {{diffuse, 3, "oD0"}}}, kPaperGoal});
  workloads.push_back({"directional_light (hand GLSL)", "directional_light.vsh",
                       HandWritten{kDirectionalLightBody, 13, {{0, 0, 3}, {1, 1, 3}},
                                   {{position, 4, "gl_Position"}, {diffuse, 4, "oD0"}, {specular, 4, "oD1"}}},
                       kGoal});
  workloads.push_back({"skinning (hand GLSL)", "skinning.vsh",
                       HandWritten{kSkinningBody, 30, {{0, 0, 3}, {1, 1, 2}, {2, 2, 2}, {3, 3, 3}},
                                   {{position, 4, "gl_Position"}, {diffuse, 4, "oD0"}}},
                       kGoal});
  return workloads;
}

std::string GlslType(int components) { return components == 1 ? "float" : fmt::format("vec{}", components); }

// The floor under a shader with these bindings: every input fetched in its format and every output
// written, with one copy or one add per input and nothing else. The inputs (read as vec4, as the
// translations read them) are spread over the outputs other than gl_Position: with n inputs and m
// such outputs, output k is the sum of the inputs j = k (mod m), or a copy of input k mod n when
// there are fewer inputs than outputs. gl_Position, a captured output of the hand-written shaders and
// written by every translation, gets the centre of the clip volume: a position outside the volume
// makes llvmpipe clip the point even with rasterisation discarded, which cost skinning's floor 55
// instead of 22-27 ns a vertex when it held a sum of inputs (so the old floor could exceed the shader).
std::string PassthroughSource(const std::vector<InputBinding>& inputs, const std::vector<OutputBinding>& outputs,
                              bool writes_position) {
  std::string source = "#version 300 es\nprecision highp float;\n";
  for (const InputBinding& input : inputs) {
    source += fmt::format("layout(location = {}) in vec4 in{};\n", input.location, input.location);
  }
  std::vector<const OutputBinding*> values;
  for (const OutputBinding& output : outputs) {
    if (output.varying == "gl_Position") {
      writes_position = true;
    } else {
      source += fmt::format("out {} {};\n", GlslType(output.components), output.varying);
      values.push_back(&output);
    }
  }
  source += "void main() {\n";
  const std::size_t n = inputs.size(), m = values.size();
  for (std::size_t k = 0; k < m; ++k) {
    std::vector<std::string> terms;
    for (std::size_t j = k; j < std::max(n, k + 1); j += m) {
      if (n > 0) terms.push_back(fmt::format("in{}", inputs[j % n].location));
    }
    std::string value = terms.empty() ? "vec4(0.0)" : fmt::format("{}", fmt::join(terms, " + "));
    const int components = values[k]->components;
    if (components < 4) value = fmt::format("({}).{}", value, std::string_view("xyzw").substr(0, components));
    source += fmt::format("  {} = {};\n", values[k]->varying, value);
  }
  if (writes_position) source += "  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n";
  return source + "}\n";
}

// One program at one vertex count: what both sides receive, and vs11's outputs.
struct Case {
  const Workload* workload = nullptr;
  std::optional<Program> program;
  ConstantBank constants;
  VertexArrays inputs;
  VertexArrays vs11_outputs;
  std::string glsl;
  std::vector<InputBinding> bindings;
  std::vector<OutputBinding> outputs;
  int constant_count = 0;
};

int OutputFloats(const Case& c) {
  int floats = 0;
  for (const OutputBinding& output : c.outputs) floats += output.components;
  return floats;
}

// The translation's bindings: every input register the program reads that the reference supplies,
// with the lanes up to the last one that is not GL's default (0, 0, 0, 1) in every vertex; every
// output register the program writes, as the translation declares it.
void BindTranslation(Case& c, const VertexArrays& supplied, std::size_t count) {
  const translate::ShaderGraph graph = translate::RecordShader(*c.program, c.constants.size());
  for (int reg = 0; reg < kInputRegisterCount; ++reg) {
    if (!graph.inputs_read[static_cast<std::size_t>(reg)] || !supplied.has(reg)) continue;
    int components = 1;
    for (int lane = 1; lane < 4; ++lane) {
      const float* values = supplied.lane(reg, lane);
      const float fill = kDefaultInput[static_cast<std::size_t>(lane)];
      if (std::any_of(values, values + count, [fill](float v) { return v != fill; })) components = lane + 1;
    }
    c.bindings.push_back({reg, reg, components});
  }
  const std::array<WriteMask, kOutputSlotCount> written = WrittenOutputLanes(*c.program);
  for (int slot = 0; slot < kOutputSlotCount; ++slot) {
    if (written[static_cast<std::size_t>(slot)].bits() == 0) continue;
    const translate::OutputVariable variable = translate::OutputVariableOf(slot);
    c.outputs.push_back({static_cast<OutputSlot>(slot), variable.components, variable.name});
  }
  translate::TranslateOptions options;
  options.target = translate::Target::kGlslEs300;
  options.clip = translate::ClipSpace::kD3d;  // the capture reads vs11_oPos either way
  options.constant_count = c.constants.size();
  options.source_name = c.workload->file;
  c.glsl = translate::TranslateToGlsl(*c.program, options);
  c.constant_count = c.constants.size();
}

std::optional<Case> BuildCase(const Workload& workload, std::size_t count, std::string& error) {
  const std::filesystem::path path = ProgramPath(workload.file);
  vs11::ProgramForVerify loaded = vs11::LoadProgramForVerify(path);
  const vs11::ReferenceInfo* info = vs11::FindReference(loaded.metadata.reference);
  if (!loaded.program || info == nullptr) {
    error = fmt::format("{}: cannot load the program or its reference", path.string());
    return std::nullopt;
  }
  vs11::ReferenceOptions options;
  options.coefficients = BenchCoefficients();
  options.samples = static_cast<int>(count);
  options.seed = kBenchSeed;
  vs11::Result<vs11::ReferenceCase> reference = info->build(loaded.metadata, options);
  if (!reference) {
    error = reference.message();
    return std::nullopt;
  }

  Case c;
  c.workload = &workload;
  c.program = std::move(loaded.program);
  c.constants = std::move(reference->constants);
  if (workload.hand_written) {
    c.glsl = std::string(kGlslPrelude) + workload.hand_written->body;
    c.bindings = workload.hand_written->inputs;
    c.outputs = workload.hand_written->outputs;
    c.constant_count = workload.hand_written->constant_count;
  } else {
    BindTranslation(c, reference->inputs, count);
  }
  std::vector<int> registers;
  for (const InputBinding& input : c.bindings) registers.push_back(input.reg);
  c.inputs = MakeInputArrays(count, registers);
  // The sh9 reference appends 14 fixed normals to its `samples`: only the first `count` are used.
  for (const InputBinding& input : c.bindings) {
    for (int lane = 0; lane < 4; ++lane) {
      const float* source = reference->inputs.lane(input.reg, lane);
      if (lane < input.components) {
        std::copy(source, source + count, c.inputs.lane(input.reg, lane));
        continue;
      }
      // GL supplies the lanes beyond the attribute's size as (0, 0, 0, 1): the reference must agree.
      const float fill = kDefaultInput[static_cast<std::size_t>(lane)];
      if (std::any_of(source, source + count, [fill](float v) { return v != fill; })) {
        error = fmt::format("{}: v{} lane {} is not the default {} that GL supplies", workload.name, input.reg, lane,
                            fill);
        return std::nullopt;
      }
      c.inputs.FillUniform(input.reg, lane, fill);
    }
  }
  c.vs11_outputs = MakeOutputArrays(count, *c.program);
  if (const Status ran = MakeEngine("jit", *c.program, c.constants).value()->Run(c.inputs, c.vs11_outputs); !ran) {
    error = fmt::format("{}: the jit engine: {}", workload.name, ran.message());
    return std::nullopt;
  }
  return c;
}

std::vector<GlAttribute> Attributes(const Case& c) {
  std::vector<GlAttribute> attributes;
  const std::size_t count = c.inputs.count();
  for (const InputBinding& input : c.bindings) {
    GlAttribute attribute{input.location, input.components, std::vector<float>(count * input.components)};
    for (int lane = 0; lane < input.components; ++lane) {
      const float* source = c.inputs.lane(input.reg, lane);
      for (std::size_t v = 0; v < count; ++v) attribute.data[v * input.components + lane] = source[v];
    }
    attributes.push_back(std::move(attribute));
  }
  return attributes;
}

std::vector<float> ConstantFloats(const Case& c) {
  std::vector<float> floats;
  for (int i = 0; i < c.constant_count; ++i) {
    for (float v : c.constants[i]) floats.push_back(v);
  }
  return floats;
}

// How llvmpipe's outputs agree with vs11's: the largest |a - b| / max(1, |a|) over every lane, and
// the share of bit-identical lanes.
json Agreement(const Case& c, const std::vector<float>& gl_outputs) {
  const std::size_t count = c.inputs.count();
  const int stride = OutputFloats(c);
  double worst = 0.0, worst_abs = 0.0;
  std::size_t identical = 0, total = 0;
  json by_output = json::object();
  int offset = 0;
  for (const OutputBinding& output : c.outputs) {
    const std::size_t identical_before = identical;
    for (int lane = 0; lane < output.components; ++lane) {
      const float* ours = c.vs11_outputs.lane(static_cast<int>(output.slot), lane);
      for (std::size_t v = 0; v < count; ++v) {
        const float a = ours[v], b = gl_outputs[v * stride + offset + lane];
        const double difference = std::isnan(a) || std::isnan(b) ? INFINITY : std::fabs(double{a} - b);
        worst_abs = std::max(worst_abs, difference);
        worst = std::max(worst, difference / std::max(1.0, std::fabs(double{a})));
        identical += std::memcmp(&a, &b, sizeof a) == 0;
        ++total;
      }
    }
    offset += output.components;
    by_output[output.varying] = static_cast<double>(identical - identical_before) /
                                static_cast<double>(count * static_cast<std::size_t>(output.components));
  }
  return {{"max_scaled_difference", worst},
          {"max_abs_difference", worst_abs},
          {"identical_fraction", static_cast<double>(identical) / static_cast<double>(total)},
          {"identical_fraction_by_output", by_output}};
}

// A timed workload: `run(calls)` processes every vertex `calls` times.
struct Timed {
  std::function<void(int)> run;
  std::vector<double> samples;  // ns per vertex
};

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Wall time, or the CPU time of every thread of the process (llvmpipe's included), in ns. On a
// machine shared beyond its cores, CPU time leaves out the time the process waits for a core.
double NowNs(bool cpu_time) {
  timespec now{};
  clock_gettime(cpu_time ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) * 1e9 + static_cast<double>(now.tv_nsec);
}

// Times the workloads in turns (one repetition of each per round, after one untimed round), so that
// the machine's changing load falls on all of them alike; samples[r] is round r's ns per vertex.
void TimeInTurns(std::vector<Timed>& workloads, std::size_t count, int repetitions, bool cpu_time) {
  const int calls = static_cast<int>(std::max<std::size_t>(1, kVerticesPerRepetition / count));
  for (Timed& w : workloads) w.run(calls);
  for (int r = 0; r < repetitions; ++r) {
    for (Timed& w : workloads) {
      const double start = NowNs(cpu_time);
      w.run(calls);
      w.samples.push_back((NowNs(cpu_time) - start) / (static_cast<double>(calls) * static_cast<double>(count)));
    }
  }
}

// In the child: for every case, llvmpipe's agreement with vs11, then llvmpipe's shader, its
// passthrough, vs11's jit and vs11's batch engine timed in turns. {"error": ...} when anything fails.
json Measure(const std::vector<Case>& cases, std::optional<int> lp_threads, int repetitions, bool cpu_time) {
  const Result<std::string> renderer = CreateLlvmpipeContext(lp_threads);
  if (!renderer) return {{"error", "cannot create the llvmpipe context: " + renderer.message()}};
  if (renderer->find("llvmpipe") == std::string::npos) {
    return {{"error", fmt::format("GL_RENDERER is '{}', not llvmpipe", *renderer)}, {"renderer", *renderer}};
  }
  json result = {{"renderer", *renderer}, {"programs", json::array()}};
  // llvmpipe starts its rasteriser threads with the context: the count shows LP_NUM_THREADS at work.
  result["process_threads"] = std::distance(std::filesystem::directory_iterator("/proc/self/task"),
                                            std::filesystem::directory_iterator());
  for (const Case& c : cases) {
    const std::vector<GlAttribute> attributes = Attributes(c);
    std::vector<std::string> varyings;
    for (const OutputBinding& output : c.outputs) varyings.push_back(output.varying);
    const int output_floats = OutputFloats(c);
    const std::size_t vertices = c.inputs.count();  // sh_order0 reads no attribute
    const auto failed = [&](const Diagnostic& error) -> json {
      return {{"error", fmt::format("{}: {}", c.workload->name, error.message)}};
    };
    Result<std::unique_ptr<TransformFeedbackRun>> shaded =
        TransformFeedbackRun::Create(c.glsl, varyings, output_floats, attributes, ConstantFloats(c), vertices);
    if (!shaded) return failed(shaded.error());
    Result<std::unique_ptr<TransformFeedbackRun>> passthrough =
        TransformFeedbackRun::Create(PassthroughSource(c.bindings, c.outputs, !c.workload->hand_written), varyings,
                                     output_floats, attributes, {}, vertices);
    if (!passthrough) return failed(passthrough.error());
    const Result<std::vector<float>> outputs = (*shaded)->DrawAndRead();
    if (!outputs) return failed(outputs.error());
    json entry = Agreement(c, *outputs);

    Status drawn;  // the first failed draw's or engine run's error
    const auto draw = [&](TransformFeedbackRun& run) {
      return [&drawn, target = &run](int calls) {
        if (Status status = target->Draw(calls); drawn.ok()) drawn = std::move(status);
      };
    };
    VertexArrays vs11_outputs = MakeOutputArrays(c.inputs.count(), *c.program);
    const auto engine_run = [&](std::string kind) {
      std::shared_ptr<Engine> engine = MakeEngine(kind, *c.program, c.constants).value();
      return [&, engine](int calls) {
        for (int k = 0; k < calls; ++k) {
          if (Status status = engine->Run(c.inputs, vs11_outputs); drawn.ok()) drawn = std::move(status);
        }
      };
    };
    std::vector<Timed> workloads = {
        {draw(**shaded), {}}, {draw(**passthrough), {}}, {engine_run("jit"), {}}, {engine_run("batch"), {}}};
    TimeInTurns(workloads, c.inputs.count(), repetitions, cpu_time);
    if (!drawn) return failed(drawn.error());
    entry["llvmpipe"] = Median(workloads[0].samples);
    entry["passthrough"] = Median(workloads[1].samples);
    entry["jit"] = Median(workloads[2].samples);
    entry["batch"] = Median(workloads[3].samples);
    // The shading alone: the median of each round's difference, which cancels load shared by the
    // two draws of a round better than the difference of the medians does.
    std::vector<double> shading;
    for (int r = 0; r < repetitions; ++r) shading.push_back(workloads[0].samples[r] - workloads[1].samples[r]);
    entry["shading"] = Median(shading);
    result["programs"].push_back(entry);
  }
  return result;
}

// Runs `measure` in a child process and returns what it sent back.
template <class Measure>
json InChild(Measure&& measure) {
  std::fflush(nullptr);
  int fds[2];
  if (pipe(fds) != 0) return {{"error", "pipe() failed"}};
  const pid_t pid = fork();
  if (pid < 0) return {{"error", "fork() failed"}};
  if (pid == 0) {
    close(fds[0]);
    const std::string text = measure().dump();
    for (std::size_t done = 0; done < text.size();) {
      const ssize_t n = write(fds[1], text.data() + done, text.size() - done);
      if (n <= 0) _exit(1);
      done += static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty()) {
    return {{"error", WIFSIGNALED(status) ? fmt::format("the llvmpipe process died of signal {}", WTERMSIG(status))
                                          : std::string("the llvmpipe process sent no result")}};
  }
  return json::parse(text);
}

struct Options {
  std::vector<std::size_t> vertices = {1024, 65536, 1048576};
  int repetitions = 15;
  bool cpu_time = false;
  double tolerance = 1e-5;
  std::string json_path;
  std::vector<std::string> programs;  // run only the rows whose name contains one of these
};

std::string ThreadsLabel(const json& setting) {
  return setting["lp_threads"].is_null() ? std::string("default") : fmt::format("{}", setting["lp_threads"].get<int>());
}

std::string LoadAverage() {
  std::ifstream file("/proc/loadavg");
  std::string one, five, fifteen;
  file >> one >> five >> fifteen;
  return fmt::format("{} {} {}", one, five, fifteen);
}

// One markdown table per llvmpipe setting. Returns false when a check failed (no llvmpipe, a GL
// error, or outputs out of tolerance).
bool PrintReport(const json& report) {
  const double tolerance = report["tolerance"];
  bool ok = true;
  fmt::print("vs11 jit ISA: {}; load average at the start: {}; ns per vertex ({}), medians of {}\n",
             report["isa"].get<std::string>(), report["load"].get<std::string>(), report["clock"].get<std::string>(),
             report["repetitions"].get<int>());
  fmt::print("shading = median over rounds of (llvmpipe - passthrough); e2e = llvmpipe / vs11 jit; "
             "speed-up = shading / vs11 jit\n");
  for (const json& setting : report["settings"]) {
    fmt::print("\nllvmpipe, LP_NUM_THREADS={}: {}\n\n", ThreadsLabel(setting),
               setting.contains("renderer") ? fmt::format("{}, {} threads in its process",
                                                          setting["renderer"].get<std::string>(),
                                                          setting["process_threads"].get<int>())
                                            : "no renderer");
    fmt::print("| vertices | program | llvmpipe | passthrough | shading | vs11 jit | vs11 batch | e2e | speed-up | goal "
               "| max scaled diff | bit-equal |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const json& row : setting["rows"]) {
      const std::string head = fmt::format("| {} | {} |", row["vertices"].get<std::size_t>(), row["program"].get<std::string>());
      if (row.contains("error")) {
        fmt::print("{} error: {} |\n", head, row["error"].get<std::string>());
        fmt::print(stderr, "compare_llvmpipe: {}\n", row["error"].get<std::string>());
        ok = false;
        continue;
      }
      const double llvmpipe = row["llvmpipe"], passthrough = row["passthrough"], jit = row["jit"];
      const double shading = row["shading"], speedup = shading / jit, goal = row["goal"];
      const double difference = row["max_scaled_difference"];
      if (!(difference <= tolerance)) ok = false;
      fmt::print("{} {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.2f} | {:.1f}x | {:.2f}x | {} {:g}x | {:.2g}{} | {:.1f} % |\n",
                 head, llvmpipe, passthrough, shading, jit, row["batch"].get<double>(),
                 llvmpipe / jit, speedup, speedup >= goal ? "met, >=" : "missed, <", goal, difference,
                 difference <= tolerance ? "" : " (over tolerance)", 100.0 * row["identical_fraction"].get<double>());
    }
  }
  if (!ok) fmt::print(stderr, "compare_llvmpipe: FAILED (see the errors above, or outputs over tolerance {:g})\n", tolerance);
  return ok;
}

int Run(const Options& options) {
  const std::vector<JitIsa> isas = jit::SupportedIsas();
  json report = {{"isa", isas.empty() ? std::string("none (batch kernels)") : std::string(kJitIsaNames.Name(isas.back()))},
                 {"load", LoadAverage()},
                 {"repetitions", options.repetitions},
                 {"clock", options.cpu_time ? "process CPU time" : "wall"},
                 {"tolerance", options.tolerance},
                 {"settings", json::array({{{"lp_threads", 1}}, {{"lp_threads", nullptr}}})}};
  for (json& setting : report["settings"]) setting["rows"] = json::array();
  std::vector<Workload> workloads = Workloads();
  if (!options.programs.empty()) {
    std::erase_if(workloads, [&](const Workload& workload) {
      return std::none_of(options.programs.begin(), options.programs.end(),
                          [&](const std::string& name) { return workload.name.find(name) != std::string::npos; });
    });
    if (workloads.empty()) {
      fmt::print(stderr, "compare_llvmpipe: no program's name contains any --program given\n");
      return 1;
    }
  }
  for (std::size_t count : options.vertices) {
    std::vector<Case> cases;
    for (const Workload& workload : workloads) {
      std::string error;
      std::optional<Case> c = BuildCase(workload, count, error);
      if (!c) {
        fmt::print(stderr, "compare_llvmpipe: {}\n", error);
        return 1;
      }
      cases.push_back(std::move(*c));
    }
    for (json& setting : report["settings"]) {
      const std::optional<int> threads =
          setting["lp_threads"].is_null() ? std::nullopt : std::optional<int>(setting["lp_threads"].get<int>());
      fmt::print(stderr, "compare_llvmpipe: {} vertices, llvmpipe with LP_NUM_THREADS={}\n", count,
                 ThreadsLabel(setting));
      const json results = InChild([&] { return Measure(cases, threads, options.repetitions, options.cpu_time); });
      for (const char* key : {"renderer", "process_threads"}) {
        if (results.contains(key)) setting[key] = results[key];
      }
      for (std::size_t i = 0; i < cases.size(); ++i) {
        json row = {{"vertices", count}, {"program", cases[i].workload->name}, {"goal", cases[i].workload->goal}};
        if (results.contains("error")) {
          row["error"] = results["error"];
        } else {
          row.update(results["programs"][i]);
        }
        setting["rows"].push_back(std::move(row));
      }
    }
  }
  const bool ok = PrintReport(report);
  if (!options.json_path.empty()) {
    if (const Status written = WriteFileAtomically(options.json_path, report.dump(2) + "\n"); !written) {
      fmt::print(stderr, "compare_llvmpipe: {}\n", written.message());
      return 1;
    }
  }
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace vs11::bench::llvmpipe

int main(int argc, char** argv) {
  vs11::bench::llvmpipe::Options options;
  CLI::App app{"vs11 against Mesa's llvmpipe: every program of programs/ (through vs11's GLSL ES translation) and "
               "three hand-written GLSL translations, on the same inputs, timed side by side (ns per vertex) beside "
               "each program's passthrough floor, and their outputs compared"};
  app.add_option("--vertices", options.vertices, "vertex counts to run")
      ->check(CLI::Range(1, 1 << 24))
      ->capture_default_str();
  app.add_option("--repetitions", options.repetitions, "timed repetitions per figure (the median is reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--tolerance", options.tolerance,
                 "largest |llvmpipe - vs11| / max(1, |vs11|) accepted on any output lane")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--cpu-time", options.cpu_time,
               "time by the process's CPU time (every thread) instead of wall time: steadier on a machine shared "
               "beyond its cores");
  app.add_option("--json", options.json_path, "also write every figure to this JSON file");
  app.add_option("--program", options.programs,
                 "run only the rows whose name contains this (repeatable), e.g. skinning or 'hand GLSL'");
  app.footer("Exit status: 0 success, 1 llvmpipe unavailable or its outputs out of tolerance, 2 a usage error.\n\n"
             "Examples:\n"
             "  build/bench/vs11_compare_llvmpipe\n"
             "  build/bench/vs11_compare_llvmpipe --vertices 1024 --repetitions 3 --json llvmpipe.json\n"
             "  build/bench/vs11_compare_llvmpipe --vertices 65536 --repetitions 3 --program skinning");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "compare_llvmpipe: error: {}\nRun with --help for more information.\n", e.what());
    return vs11::bench::llvmpipe::kUsageError;
  }
  return vs11::bench::llvmpipe::Run(options);
}
