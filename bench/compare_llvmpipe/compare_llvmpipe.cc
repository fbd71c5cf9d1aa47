// vs11 against Mesa's llvmpipe on the same vertex programs, inputs and constants, in one run.
//
// For each vertex count, each program (the paper's sh9_irradiance, directional_light, skinning) is
// built from its reference's inputs and constants (irradiance/report/program_references.h) and run
//  * by llvmpipe, as the GLSL translation in shaders.h, through transform feedback with the
//    rasterizer discarded, once with LP_NUM_THREADS=1 and once with Mesa's default thread count;
//  * by llvmpipe as a `passthrough` shader with the program's inputs and outputs and no arithmetic:
//    llvmpipe's cost of fetching the vertices and copying the outputs into the transform-feedback
//    buffer. llvmpipe's time minus this is its shading alone;
//  * by vs11's jit and batch engines (one thread).
// Each llvmpipe setting runs in a child process (fork), since Mesa reads LP_NUM_THREADS once, when
// the display is initialised; the child sends its results back as JSON through a pipe.
//
// Times are ns per vertex, medians of --repetitions, each repetition at least 2^20 vertices (many
// draws or Run calls for the small counts), after one untimed warm-up repetition; a llvmpipe
// repetition ends with glFinish. --cpu-time measures the CPU time of the whole process instead of
// wall time. The four workloads of a program take turns, one repetition each per
// round; the shading alone is the median of the rounds' (llvmpipe - passthrough). llvmpipe's outputs are read back once per program and compared
// with vs11's jit outputs: the largest |difference| / max(1, |vs11|) over every output lane must stay
// within --tolerance.

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
#include "vm/gl/gl_runner.h"
#include "bench/compare_llvmpipe/shaders.h"
#include "irradiance/report/program_references.h"
#include "irradiance/report/verify.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/jit_compiler.h"

namespace vs11::bench::llvmpipe {
namespace {

using nlohmann::json;
using gl::CreateLlvmpipeContext;
using gl::GlAttribute;
using gl::TransformFeedbackRun;

constexpr int kUsageError = 2;
constexpr std::size_t kVerticesPerRepetition = std::size_t{1} << 20;

// An input register as a GL attribute: its first `components` lanes (the rest read (0, 0, 0, 1)).
struct InputBinding {
  int reg;
  int components;
};

// An output register as a transform-feedback varying: its first `components` lanes.
struct OutputBinding {
  OutputSlot slot;
  int components;
  const char* varying;
};

struct ProgramSpec {
  const char* name;
  const char* file;  // in programs/
  const char* glsl_body;
  int constant_count;
  std::vector<InputBinding> inputs;
  std::vector<OutputBinding> outputs;
  double goal;  // vs11 jit must be this many times faster than llvmpipe's shading alone
};

const std::vector<ProgramSpec>& Programs() {
  static const std::vector<ProgramSpec> programs = {
      {"sh9_irradiance (paper)", "sh9_irradiance.vsh", kSh9IrradianceBody, 7, {{0, 3}},
       {{OutputSlot::kDiffuse, 3, "oD0"}}, 5.0},
      {"directional_light", "directional_light.vsh", kDirectionalLightBody, 13, {{0, 3}, {1, 3}},
       {{OutputSlot::kPosition, 4, "gl_Position"}, {OutputSlot::kDiffuse, 4, "oD0"},
        {OutputSlot::kSpecular, 4, "oD1"}},
       3.0},
      {"skinning", "skinning.vsh", kSkinningBody, 30, {{0, 3}, {1, 2}, {2, 2}, {3, 3}},
       {{OutputSlot::kPosition, 4, "gl_Position"}, {OutputSlot::kDiffuse, 4, "oD0"}}, 3.0},
  };
  return programs;
}

int OutputFloats(const ProgramSpec& spec) {
  int floats = 0;
  for (const OutputBinding& output : spec.outputs) floats += output.components;
  return floats;
}

std::string GlslType(int components) { return components == 1 ? "float" : fmt::format("vec{}", components); }

// The program's inputs copied to its outputs, component after component (cycling through the inputs
// when the outputs hold more), with no arithmetic.
std::string PassthroughSource(const ProgramSpec& spec) {
  std::string source = "#version 300 es\nprecision highp float;\n";
  std::vector<std::string> components;
  for (std::size_t i = 0; i < spec.inputs.size(); ++i) {
    const InputBinding& input = spec.inputs[i];
    source += fmt::format("layout(location = {}) in {} v{};\n", i, GlslType(input.components), input.reg);
    for (int c = 0; c < input.components; ++c) components.push_back(fmt::format("v{}.{}", input.reg, "xyzw"[c]));
  }
  for (const OutputBinding& output : spec.outputs) {
    if (std::string_view(output.varying) != "gl_Position") {
      source += fmt::format("out {} {};\n", GlslType(output.components), output.varying);
    }
  }
  source += "void main() {\n";
  std::size_t next = 0;
  for (const OutputBinding& output : spec.outputs) {
    std::vector<std::string> parts;
    for (int c = 0; c < output.components; ++c) parts.push_back(components[next++ % components.size()]);
    source += fmt::format("  {} = {}({});\n", output.varying, GlslType(output.components), fmt::join(parts, ", "));
  }
  return source + "}\n";
}

// One program at one vertex count: what both sides receive, and vs11's outputs.
struct Case {
  const ProgramSpec* spec = nullptr;
  std::optional<Program> program;
  ConstantBank constants;
  VertexArrays inputs;
  VertexArrays vs11_outputs;
};

std::optional<Case> BuildCase(const ProgramSpec& spec, std::size_t count, std::string& error) {
  const std::filesystem::path path = ProgramPath(spec.file);
  irradiance::ProgramForVerify loaded = irradiance::LoadProgramForVerify(path);
  const irradiance::ReferenceInfo* info = irradiance::FindReference(loaded.metadata.reference);
  if (!loaded.program || info == nullptr) {
    error = fmt::format("{}: cannot load the program or its reference", path.string());
    return std::nullopt;
  }
  irradiance::ReferenceOptions options;
  options.coefficients = BenchCoefficients();
  options.samples = static_cast<int>(count);
  options.seed = kBenchSeed;
  std::optional<irradiance::ReferenceCase> reference = info->build(loaded.metadata, options, error);
  if (!reference) return std::nullopt;

  Case c;
  c.spec = &spec;
  c.program = std::move(loaded.program);
  c.constants = std::move(reference->constants);
  std::vector<int> registers;
  for (const InputBinding& input : spec.inputs) registers.push_back(input.reg);
  c.inputs = MakeInputArrays(count, registers);
  // The sh9 reference appends 14 fixed normals to its `samples`: only the first `count` are used.
  for (const InputBinding& input : spec.inputs) {
    for (int lane = 0; lane < 4; ++lane) {
      const float* source = reference->inputs.lane(input.reg, lane);
      if (lane < input.components) {
        std::copy(source, source + count, c.inputs.lane(input.reg, lane));
        continue;
      }
      // GL supplies the lanes beyond the attribute's size as (0, 0, 0, 1): the reference must agree.
      const float fill = kDefaultInput[static_cast<std::size_t>(lane)];
      if (std::any_of(source, source + count, [fill](float v) { return v != fill; })) {
        error = fmt::format("{}: v{} lane {} is not the default {} that GL supplies", spec.name, input.reg, lane, fill);
        return std::nullopt;
      }
      c.inputs.FillUniform(input.reg, lane, fill);
    }
  }
  c.vs11_outputs = MakeOutputArrays(count, *c.program);
  MakeEngine(EngineKind::kJit, *c.program, c.constants)->Run(c.inputs, c.vs11_outputs);
  return c;
}

std::vector<GlAttribute> Attributes(const Case& c) {
  std::vector<GlAttribute> attributes;
  const std::size_t count = c.inputs.count();
  for (std::size_t i = 0; i < c.spec->inputs.size(); ++i) {
    const InputBinding& input = c.spec->inputs[i];
    GlAttribute attribute{static_cast<int>(i), input.components, std::vector<float>(count * input.components)};
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
  for (int i = 0; i < c.spec->constant_count; ++i) {
    for (float v : c.constants[i]) floats.push_back(v);
  }
  return floats;
}

// How llvmpipe's outputs agree with vs11's: the largest |a - b| / max(1, |a|) over every lane, and
// the share of bit-identical lanes.
json Agreement(const Case& c, const std::vector<float>& gl_outputs) {
  const std::size_t count = c.inputs.count();
  const int stride = OutputFloats(*c.spec);
  double worst = 0.0, worst_abs = 0.0;
  std::size_t identical = 0, total = 0;
  json by_output = json::object();
  int offset = 0;
  for (const OutputBinding& output : c.spec->outputs) {
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
  std::string error;
  const std::optional<std::string> renderer = CreateLlvmpipeContext(lp_threads, error);
  if (!renderer) return {{"error", "cannot create the llvmpipe context: " + error}};
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
    for (const OutputBinding& output : c.spec->outputs) varyings.push_back(output.varying);
    const int output_floats = OutputFloats(*c.spec);
    auto shaded = TransformFeedbackRun::Create(std::string(kGlslPrelude) + c.spec->glsl_body, varyings, output_floats,
                                               attributes, ConstantFloats(c), error);
    auto passthrough = shaded ? TransformFeedbackRun::Create(PassthroughSource(*c.spec), varyings, output_floats,
                                                             attributes, {}, error)
                              : nullptr;
    std::optional<std::vector<float>> outputs;
    if (passthrough) outputs = shaded->DrawAndRead(error);
    if (!outputs) return {{"error", fmt::format("{}: {}", c.spec->name, error)}};
    json entry = Agreement(c, *outputs);

    bool drawn = true;
    const auto draw = [&](TransformFeedbackRun& run) {
      return [&drawn, &error, target = &run](int calls) { drawn = target->Draw(calls, error) && drawn; };
    };
    VertexArrays vs11_outputs = MakeOutputArrays(c.inputs.count(), *c.program);
    const auto engine_run = [&](EngineKind kind) {
      std::shared_ptr<Engine> engine = MakeEngine(kind, *c.program, c.constants);
      return [&, engine](int calls) {
        for (int k = 0; k < calls; ++k) engine->Run(c.inputs, vs11_outputs);
      };
    };
    std::vector<Timed> workloads = {{draw(*shaded), {}}, {draw(*passthrough), {}},
                                    {engine_run(EngineKind::kJit), {}}, {engine_run(EngineKind::kBatch), {}}};
    TimeInTurns(workloads, c.inputs.count(), repetitions, cpu_time);
    if (!drawn) return {{"error", fmt::format("{}: {}", c.spec->name, error)}};
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
  json report = {{"isa", isas.empty() ? std::string("none (batch kernels)") : std::string(jit::IsaName(isas.back()))},
                 {"load", LoadAverage()},
                 {"repetitions", options.repetitions},
                 {"clock", options.cpu_time ? "process CPU time" : "wall"},
                 {"tolerance", options.tolerance},
                 {"settings", json::array({{{"lp_threads", 1}}, {{"lp_threads", nullptr}}})}};
  for (json& setting : report["settings"]) setting["rows"] = json::array();
  for (std::size_t count : options.vertices) {
    std::vector<Case> cases;
    for (const ProgramSpec& spec : Programs()) {
      std::string error;
      std::optional<Case> c = BuildCase(spec, count, error);
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
        json row = {{"vertices", count}, {"program", cases[i].spec->name}, {"goal", cases[i].spec->goal}};
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
    if (std::optional<std::string> error = WriteFileAtomically(options.json_path, report.dump(2) + "\n")) {
      fmt::print(stderr, "compare_llvmpipe: {}\n", *error);
      return 1;
    }
  }
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace vs11::bench::llvmpipe

int main(int argc, char** argv) {
  vs11::bench::llvmpipe::Options options;
  CLI::App app{"vs11 against Mesa's llvmpipe: the paper's vertex program, directional_light and skinning on the "
               "same inputs, timed side by side (ns per vertex) and their outputs compared"};
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
  app.footer("Exit status: 0 success, 1 llvmpipe unavailable or its outputs out of tolerance, 2 a usage error.\n\n"
             "Examples:\n"
             "  build/bench/vs11_compare_llvmpipe\n"
             "  build/bench/vs11_compare_llvmpipe --vertices 1024 --repetitions 3 --json llvmpipe.json");
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
