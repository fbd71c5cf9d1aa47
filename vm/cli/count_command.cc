// vs11 count: static instruction figures and measured time per vertex for each engine.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <random>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "vm/cli/cli_support.h"
#include "vm/cli/commands.h"
#include "vm/core/thread_pool.h"
#include "vm/engines/engine_factory.h"
#include "vm/reference/sphere_normals.h"

namespace vs11::cli {
namespace {

constexpr std::size_t kTimedVertices = 65536;
constexpr int kTimedRepeats = 5;  // the best of these is reported: the least disturbed run

std::vector<int> InputRegistersRead(const Program& program) {
  std::vector<int> registers;
  for (const Instruction& instruction : program.instructions) {
    const OpcodeInfo& info = instruction.info();
    for (int s = 0; s < info.source_count(); ++s) {
      const RegisterRef& reg = instruction.sources[s].reg;
      if (reg.file == RegisterFile::kInput && std::find(registers.begin(), registers.end(), reg.index) == registers.end()) {
        registers.push_back(reg.index);
      }
    }
  }
  return registers;
}

double MeasureNsPerVertex(std::string_view engine_name, const Program& program, int threads) {
  ConstantBank constants;
  std::mt19937 random(12345);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f);
  for (int i = 0; i < constants.size(); ++i) constants[i] = {value(random), value(random), value(random), value(random)};
  std::vector<int> registers = InputRegistersRead(program);
  VertexArrays inputs = MakeInputArrays(kTimedVertices, registers);
  std::vector<glm::dvec3> normals = SphereNormals(static_cast<int>(kTimedVertices));
  for (int reg : registers) {
    for (std::size_t i = 0; i < kTimedVertices; ++i) {
      for (int c = 0; c < 3; ++c) inputs.lane(reg, c)[i] = static_cast<float>(normals[i][c]);
    }
  }
  VertexArrays outputs = MakeOutputArrays(kTimedVertices, program);
  std::unique_ptr<Engine> engine = MakeEngineOrFail(engine_name, program, constants, {threads});
  double best = 1e300;
  for (int repeat = 0; repeat < kTimedRepeats; ++repeat) {
    auto start = std::chrono::steady_clock::now();
    RunOrFail(*engine, inputs, outputs);
    std::chrono::duration<double, std::nano> elapsed = std::chrono::steady_clock::now() - start;
    best = std::min(best, elapsed.count() / static_cast<double>(kTimedVertices));
  }
  return best;
}

}  // namespace

void AddCountCommand(CLI::App& app) {
  struct Args {
    std::vector<std::string> programs;
    bool json = false;
    bool no_timing = false;
    ProgramFlags flags;
    int threads = 1;
  };
  auto args = std::make_shared<Args>();
  CLI::App* command = app.add_subcommand("count", "Instruction counts, slots, registers and ns per vertex of programs");
  command->footer(
      "Columns: executable instructions, instruction slots (macros and multi-slot instructions as the\n"
      "spec counts them), distinct constant, temporary and input registers, instructions executed per\n"
      "vertex (exec/v; vs_1_1 has no flow control: every instruction runs once), and the best of 5 timed\n"
      "runs over 65536 normals on each engine (ref, batch, jit).\n"
      "A program that does not load is reported on stderr and left out; the status is then 1.\n\n"
      "Examples:\n  vs11 count programs/*.vsh\n  vs11 count programs/sh9_irradiance.vsh --json");
  command->add_option("programs", args->programs, "Programs (.vsh or .vso; - reads standard input)")->required();
  command->add_flag("--json", args->json, "Print a JSON array of objects instead of a table");
  command->add_flag("--no-timing", args->no_timing, "Skip the timed runs");
  command->add_option("--threads", args->threads, "Threads for the batch and jit engines")->check(CLI::Range(1, kMaxThreadsOption));
  args->flags.AddTo(*command);
  command->callback([args] {
    nlohmann::json rows = nlohmann::json::array();
    // A program that does not load is reported and skipped; the others are still counted.
    CheckInputsAndOutputs(args->programs, {});
    std::vector<std::pair<std::string, Program>> programs;
    bool any_failed = false;
    for (const std::string& path : args->programs) {
      try {
        programs.emplace_back(path, LoadProgramOrFail(path, args->flags));
      } catch (const CommandFailure&) {
        any_failed = true;
      }
    }
    for (const auto& [path, program] : programs) {
      ProgramStats stats = ComputeStats(program);
      nlohmann::json row = {{"file", path},                      {"instructions", stats.instructions},
                            {"slots", stats.slots},              {"constants", stats.constants},
                            {"temporaries", stats.temporaries},  {"inputs", stats.inputs},
                            {"dynamic_instructions_per_vertex", stats.instructions},
                            {"ns_per_vertex", nlohmann::json::object()}};
      if (!args->no_timing) {
        // The table's columns: the CPU engines (the gl engine's time is the driver's, not the machine's).
        for (const char* engine : {"ref", "batch", "jit"}) {
          row["ns_per_vertex"][engine] = MeasureNsPerVertex(engine, program, args->threads);
        }
      }
      rows.push_back(std::move(row));
    }
    if (args->json) {
      std::printf("%s\n", rows.dump(2).c_str());
      if (any_failed) throw CommandFailure{1};
      return;
    }
    std::printf("%-44s %6s %6s %6s %6s %6s %6s %10s %10s %10s\n", "program", "instr", "slots", "const", "temps", "inputs",
                "exec/v", "ref ns/v", "batch ns/v", "jit ns/v");
    for (const nlohmann::json& row : rows) {
      auto ns = [&](const char* engine) {
        return row["ns_per_vertex"].contains(engine) ? fmt::format("{:.2f}", row["ns_per_vertex"][engine].get<double>())
                                                     : std::string("-");
      };
      std::printf("%-44s %6d %6d %6d %6d %6d %6d %10s %10s %10s\n", row["file"].get<std::string>().c_str(),
                  row["instructions"].get<int>(), row["slots"].get<int>(), row["constants"].get<int>(),
                  row["temporaries"].get<int>(), row["inputs"].get<int>(),
                  row["dynamic_instructions_per_vertex"].get<int>(), ns("ref").c_str(), ns("batch").c_str(),
                  ns("jit").c_str());
    }
    if (any_failed) throw CommandFailure{1};
  });
}

}  // namespace vs11::cli
