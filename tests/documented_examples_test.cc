// Every example the tools and READMEs show runs as written. The `Examples:` lines of every --help
// page (vs11, irrmap and each of their subcommands) and the commands in the READMEs' code blocks
// are run in a fresh temporary folder in which `programs`, `bench` and `build` point into the tree,
// after the files an example names are made from the fixture table below. An example that names a
// file the table cannot make fails, so a new example is tested the day it is written. The few that
// cannot run in a test are listed in kNotRun with the reason, and printed when skipped.

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "tests/run_tool.h"
#include "vm/mesh/npy.h"

namespace {

namespace fs = std::filesystem;

using vs11::testing::CommandResult;

const fs::path kSource = VS11_SOURCE_DIR;
const fs::path kBinary = VS11_BINARY_DIR;

// ---- what the examples may name ---------------------------------------------------------------

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// Runs a shell command in `dir` with the built tools first on PATH.
CommandResult RunShell(const fs::path& dir, const std::string& command) {
  const fs::path script = dir / ".example.sh";
  WriteText(script, command + "\n");
  // The README's Slurm job script reads the variables Slurm sets for each array task.
  const std::string line = "cd '" + dir.string() + "' && SLURM_ARRAY_TASK_ID=3 SLURM_CPUS_PER_TASK=2 PATH='" + (kBinary / "vm").string() + ":" +
                           (kBinary / "irradiance").string() + "':\"$PATH\" bash .example.sh 2>&1";
  return vs11::testing::RunCommandLine(line);
}

void WriteEnvironment(const fs::path& path, vs11::irradiance::EnvironmentLayout layout) {
  const vs11::irradiance::CubeMap sky = vs11::irradiance::MakeSky(16);
  ASSERT_EQ(vs11::irradiance::WriteCubeMap(sky, path, layout).message(), "") << path;
}

// Four crosses and all.txt, the list of them the Slurm and merge examples read.
void WriteDatasetList(const fs::path& dir) {
  for (int i = 0; i < 4; ++i) {
    WriteEnvironment(dir / fmt::format("env{}.exr", i), vs11::irradiance::EnvironmentLayout::kHorizontalCross);
  }
  WriteText(dir / "all.txt", "env*.exr\n");
}

void MakeWithTool(const fs::path& dir, const std::string& command) {
  const CommandResult made = RunShell(dir, command);
  ASSERT_EQ(made.status, 0) << "fixture: " << command << "\n" << made.output;
}

// File name as the example writes it -> how to make it in the example's folder.
const std::map<std::string, std::function<void(const fs::path&)>>& Fixtures() {
  using vs11::irradiance::EnvironmentLayout;
  static const auto* fixtures = new std::map<std::string, std::function<void(const fs::path&)>>{
      {"sh9.vso", [](const fs::path& dir) { MakeWithTool(dir, "vs11 asm programs/sh9_irradiance.vsh -o sh9.vso"); }},
      {"out/constants.vsh",
       [](const fs::path& dir) { MakeWithTool(dir, "irrmap --face-size 16 --coefficients-only --out out"); }},
      {"light.vsh",
       [](const fs::path& dir) {
         WriteText(dir / "light.vsh",
                   "vs_1_1\ndcl_position v0\ndcl_normal v1\nmov oPos, v0\ndp3 r0, v1, c4\nmax oD0, r0, -r0\n");
       }},
      {"lit.csv",  // as `vs11 run light.vsh ... --out lit.csv` writes it
       [](const fs::path& dir) {
         WriteText(dir / "lit.csv",
                   "oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.y,oD0.z,oD0.w\n0,0,0,1,1,1,1,1\n1,0,0,1,0,0,0,0\n"
                   "0,1,0,1,0,0,0,0\n");
       }},
      {"heights.vsh",  // vs11 run --texture: a vs_3_0 program lifting its vertices by an R32F height map
       [](const fs::path& dir) {
         WriteText(dir / "heights.vsh",
                   "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\ndcl_2d s0\nmov r0, v0\n"
                   "texldl r1, v0, s0\nadd r0.z, v0.z, r1.x\nmov o0, r0\nmov o1, r1\n");
       }},
      {"heights.npy",  // a 4 x 4 R32F texture: shape (4, 4), texel (x, y) = 10 y + x
       [](const fs::path& dir) {
         vs11::mesh::NpyArray heights;
         heights.rows = 4;
         heights.columns = 4;
         for (int i = 0; i < 16; ++i) heights.values.push_back(static_cast<float>(10 * (i / 4) + i % 4));
         const std::vector<std::uint8_t> bytes = vs11::mesh::FormatNpy(heights);
         WriteText(dir / "heights.npy", std::string(bytes.begin(), bytes.end()));
       }},
      {"positions.csv", [](const fs::path& dir) { WriteText(dir / "positions.csv", "x,y,z\n0,0,0\n1,0,0\n0,1,0\n"); }},
      {"normals.csv", [](const fs::path& dir) { WriteText(dir / "normals.csv", "nx,ny,nz\n0,0,1\n1,0,0\n0,1,0\n"); }},
      {"infinite_normals.csv",  // --float-rules: infinities times the unset (zero) constants
       [](const fs::path& dir) { WriteText(dir / "infinite_normals.csv", "nx,ny,nz\ninf,0,1\n0,-inf,0\n"); }},
      {"grace.json",
       [](const fs::path& dir) {
         std::string rows;
         for (int i = 0; i < 9; ++i) rows += std::string(i ? "," : "") + (i ? "[0.1,0.2,0.3]" : "[1,1,1]");
         WriteText(dir / "grace.json", "{\"coefficients\": [" + rows + "]}");
       }},
      {"my.vsh", [](const fs::path& dir) { fs::copy_file(kSource / "programs/sh9_vertex_ot0_hdr.vsh", dir / "my.vsh"); }},
      {"probe.hdr", [](const fs::path& dir) { WriteEnvironment(dir / "probe.hdr", EnvironmentLayout::kAngular); }},
      {"cross.exr",
       [](const fs::path& dir) { WriteEnvironment(dir / "cross.exr", EnvironmentLayout::kHorizontalCross); }},
      {"sky_{face}.exr",
       [](const fs::path& dir) { WriteEnvironment(dir / "sky_{face}.exr", EnvironmentLayout::kFaces); }},
      // irrmap batch's inputs: globs, list files, and the run's own shard of a dataset.
      {"panoramas/*.exr",
       [](const fs::path& dir) {
         fs::create_directories(dir / "panoramas");
         for (const char* name : {"a.exr", "b.exr"}) WriteEnvironment(dir / "panoramas" / name, EnvironmentLayout::kHorizontalCross);
       }},
      {"files.txt",  // --layout latlong in the example
       [](const fs::path& dir) {
         WriteEnvironment(dir / "hall.exr", EnvironmentLayout::kLatLong);
         WriteEnvironment(dir / "yard.exr", EnvironmentLayout::kLatLong);
         WriteText(dir / "files.txt", "hall.exr\nyard.exr\n");
       }},
      {"all.txt", WriteDatasetList},
      {"data/*/*.hdr",  // --shard 3/16: the fourth file is the shard's
       [](const fs::path& dir) {
         for (int i = 0; i < 4; ++i) {
           fs::create_directories(dir / "data" / fmt::format("set{}", i));
           WriteEnvironment(dir / "data" / fmt::format("set{}", i) / "probe.hdr", EnvironmentLayout::kHorizontalCross);
         }
       }},
      {"out/part-*.jsonl",  // irrmap batch-merge's parts: all.txt's inputs in two shards
       [](const fs::path& dir) {
         WriteDatasetList(dir);
         for (int k = 0; k < 2; ++k) MakeWithTool(dir, fmt::format("irrmap batch --list all.txt -o out/part-{0}.jsonl --shard {0}/2", k));
       }},
      {"wuson_out/oPos.npy",  // as the example before it writes them with --out-npy wuson_out
       [](const fs::path& dir) {
         MakeWithTool(dir, "vs11 run programs/directional_light.vsh --mesh /usr/share/assimp/models/PLY/Wuson.ply "
                           "--const c8=0,0,5,1 --missing zeros --out-npy wuson_out");
       }},
  };
  return *fixtures;
}

// Examples deliberately not run, matched by their start, with the reason (printed when skipped).
struct NotRun {
  const char* start;
  const char* reason;
};
constexpr NotRun kNotRun[] = {
    {"bash .ci/setup", "the Quick start: installs packages and builds from scratch (../shared/tools/fresh-machine-check)"},
    {"bash .ci/sanitize", "the sanitizer build and fuzzers: about 15 minutes"},
    {"build-asan/", "needs the sanitizer build"},
    {"cmake ", "configures or builds the project itself"},
    {"build/bench/vs11_bench", "a benchmark run: minutes"},
    {"build/bench/vs11_compare_llvmpipe --cpu-time", "the full llvmpipe comparison: minutes"},
    {"build/bench/vs11_gl_paths_bench", "a benchmark run: minutes"},
    {"python3 bench/compare_cmgen.py", "needs Filament's cmgen and minutes"},
    {"python3 bench/irradiance/dataset_throughput.py", "a benchmark run: about a minute on two cores"},
    {"irrmap stability", "about a minute of work on two cores; tests/irradiance/report/stability_test.cc covers it"},
};

// Examples whose documented outcome is a failed check.
const std::map<std::string, int> kExpectedStatus = {
    {"vs11 verify programs/sh9_irradiance_as_printed.vsh --reference sh9", 1},
};

const NotRun* FindNotRun(const std::string& command) {
  for (const NotRun& entry : kNotRun) {
    if (command.rfind(entry.start, 0) == 0) return &entry;
  }
  return nullptr;
}

// Makes the fixtures `command` names in a fresh folder, runs it there and checks its status.
void RunExample(const std::string& command, const std::string& where) {
  SCOPED_TRACE(where + ": " + command);
  if (const NotRun* skip = FindNotRun(command)) {
    std::printf("[ not run ] %s: %s (%s)\n", where.c_str(), command.c_str(), skip->reason);
    return;
  }
  static int counter = 0;
  const fs::path dir = fs::path(::testing::TempDir()) / ("vs11_example_" + std::to_string(++counter));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* link : {"programs", "bench"}) fs::create_directory_symlink(kSource / link, dir / link);
  fs::create_directory_symlink(kBinary, dir / "build");
  for (const auto& [name, make] : Fixtures()) {
    if (command.find(name) != std::string::npos) make(dir);
  }
  const CommandResult run = RunShell(dir, command);
  const auto expected = kExpectedStatus.find(command);
  EXPECT_EQ(run.status, expected == kExpectedStatus.end() ? 0 : expected->second) << run.output;
  std::printf("[ example ] %s: %s -> %d\n", where.c_str(), command.c_str(), run.status);
  fs::remove_all(dir);
}

// ---- --help pages -----------------------------------------------------------------------------

struct HelpPage {
  std::string tool;        // vs11 or irrmap
  std::string subcommand;  // "" for the tool's own page
};

std::string HelpText(const HelpPage& page) {
  const std::string binary = page.tool == "vs11" ? "vm/vs11" : "irradiance/irrmap";
  CommandResult help = vs11::testing::RunTool(binary, page.subcommand + " --help");
  EXPECT_EQ(help.status, 0) << help.output;
  return help.output;
}

// The indented lines under a heading such as "Examples:", up to the next blank or unindented line.
std::vector<std::string> LinesUnder(const std::string& help, const std::string& heading) {
  std::vector<std::string> lines;
  std::istringstream in(help);
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (line == heading) {
      inside = true;
    } else if (inside && line.rfind("  ", 0) == 0) {
      lines.push_back(line);
    } else {
      inside = false;
    }
  }
  return lines;
}

// The examples, comments and all (they are shell lines).
std::vector<std::string> ExampleLines(const std::string& help) {
  std::vector<std::string> examples;
  for (const std::string& line : LinesUnder(help, "Examples:")) examples.push_back(line.substr(line.find_first_not_of(' ')));
  return examples;
}

// The names listed under "Subcommands:" (their descriptions may continue on deeper-indented lines).
std::vector<std::string> SubcommandNames(const std::string& help) {
  std::vector<std::string> names;
  for (const std::string& line : LinesUnder(help, "Subcommands:")) {
    if (line.size() > 2 && line[2] != ' ') names.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  return names;
}

const std::vector<HelpPage> kHelpPages = {
    {"vs11", ""},    {"vs11", "asm"},       {"vs11", "disasm"}, {"vs11", "validate"},  {"vs11", "run"},
    {"vs11", "count"}, {"vs11", "verify"},  {"vs11", "translate"}, {"irrmap", ""},     {"irrmap", "chart"},   {"irrmap", "stability"},
    {"irrmap", "batch"}, {"irrmap", "batch-merge"},
};

TEST(DocumentedExamples, EveryHelpPageIsInTheList) {
  for (const std::string tool : {"vs11", "irrmap"}) {
    for (const std::string& sub : SubcommandNames(HelpText({tool, ""}))) {
      bool listed = false;
      for (const HelpPage& page : kHelpPages) listed |= page.tool == tool && page.subcommand == sub;
      EXPECT_TRUE(listed) << tool << " " << sub << " is a subcommand whose --help is not in kHelpPages";
    }
  }
}

class DocumentedHelpExamples : public ::testing::TestWithParam<HelpPage> {};

TEST_P(DocumentedHelpExamples, RunAsWritten) {
  const HelpPage& page = GetParam();
  const std::vector<std::string> examples = ExampleLines(HelpText(page));
  ASSERT_FALSE(examples.empty()) << page.tool << " " << page.subcommand << " --help shows no Examples:";
  for (const std::string& example : examples) {
    EXPECT_EQ(example.rfind(page.tool + " ", 0) == 0 || example == page.tool, true) << example;
    RunExample(example, page.tool + " " + page.subcommand + " --help");
  }
}

INSTANTIATE_TEST_SUITE_P(Pages, DocumentedHelpExamples, ::testing::ValuesIn(kHelpPages),
                         [](const ::testing::TestParamInfo<HelpPage>& info) {
                           std::string name = info.param.tool + (info.param.subcommand.empty() ? "" : "_" + info.param.subcommand);
                           std::replace(name.begin(), name.end(), '-', '_');  // batch-merge
                           return name;
                         });

// ---- README code blocks ---------------------------------------------------------------------------

struct CodeBlock {
  int first_line;
  std::vector<std::string> lines;
  std::string language;  // the fence's info string: ```python
};

std::vector<CodeBlock> CodeBlocks(const fs::path& markdown) {
  std::vector<CodeBlock> blocks;
  std::ifstream in(markdown);
  bool inside = false;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.rfind("```", 0) == 0) {
      inside = !inside;
      if (inside) blocks.push_back({number + 1, {}, line.substr(3)});
    } else if (inside) {
      blocks.back().lines.push_back(line);
    }
  }
  return blocks;
}

// A line a user would paste: a command of ours, with its `$ ` prompt removed; "" for anything else
// (program text, printed output, comments).
std::string CommandOf(std::string line) {
  if (line.rfind("$ ", 0) == 0) line = line.substr(2);
  for (const char* start : {"vs11 ", "irrmap", "build/", "build-asan/", "python3 ", "bash ", "cmake "}) {
    if (line.rfind(start, 0) == 0) return line;
  }
  return "";
}

// A synopsis shows optional parts in brackets or repeats with "...": it is checked, not run.
bool IsSynopsis(const std::string& command) {
  return command.find(" [") != std::string::npos || command.find("...") != std::string::npos;
}

// Every --flag a synopsis line names appears in its tool's (or subcommand's) --help.
void CheckSynopsis(const std::vector<std::string>& lines, const std::string& where) {
  std::string tool;
  for (const std::string& line : lines) {
    std::istringstream words(line);
    std::string first, second;
    words >> first >> second;
    std::string subcommand;
    if (first == "vs11" || first == "irrmap") {
      tool = first;
      const bool is_word = !second.empty() && second[0] != '-' && std::all_of(second.begin(), second.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || c == '-';  // batch-merge
      });
      if (is_word) subcommand = second;
    }
    if (tool.empty()) continue;
    const std::string help = HelpText({tool, subcommand});
    static const std::regex kFlag("--[a-z][a-z-]*");
    for (std::sregex_iterator it(line.begin(), line.end(), kFlag), end; it != end; ++it) {
      EXPECT_THAT(help, ::testing::HasSubstr(it->str())) << where << ": `" << line << "` names " << it->str()
                                                          << ", which `" << tool << " " << subcommand
                                                          << " --help` does not list";
    }
    std::printf("[ synopsis ] %s: %s (flags checked against --help)\n", where.c_str(), line.c_str());
  }
}

class DocumentedReadmeCommands : public ::testing::TestWithParam<std::string> {};

// A ```python block is a script: run whole, from the folder the examples run in, by the interpreter
// the vs11 module was built for, with the build's module on PYTHONPATH.
void RunPythonExample(const CodeBlock& block, const std::string& where) {
#ifdef VS11_PYTHON
  std::string script;
  for (const std::string& line : block.lines) script += line + "\n";
  RunExample("PYTHONPATH=build/python " VS11_PYTHON " - <<'VS11_PYTHON_EXAMPLE'\n" + script + "VS11_PYTHON_EXAMPLE",
             where);
#else
  std::printf("[ not run ] %s: a Python script (the vs11 module is not built: VS11_BUILD_PYTHON=OFF)\n",
              where.c_str());
  (void)block;
#endif
}

TEST_P(DocumentedReadmeCommands, RunAsWrittenOrAreCheckedSynopses) {
  const fs::path markdown = kSource / GetParam();
  ASSERT_TRUE(fs::exists(markdown)) << markdown;
  int commands = 0;
  for (const CodeBlock& block : CodeBlocks(markdown)) {
    if (block.language == "python") {
      RunPythonExample(block, GetParam() + ":" + std::to_string(block.first_line));
      ++commands;
      continue;
    }
    std::vector<std::string> lines;
    bool synopsis = false;
    for (std::string line : block.lines) {
      // A command continues on the next line after a trailing backslash, as in a shell.
      if (!lines.empty() && !lines.back().empty() && lines.back().back() == '\\') {
        lines.back().back() = ' ';
        lines.back() += line.substr(std::min(line.find_first_not_of(' '), line.size()));
        continue;
      }
      std::string command = CommandOf(line);
      if (command.empty()) {
        // A synopsis continues on indented lines.
        if (synopsis && line.rfind("  ", 0) == 0) lines.back() += " " + line;
        continue;
      }
      lines.push_back(command);
      synopsis |= IsSynopsis(command);
    }
    const std::string where = GetParam() + ":" + std::to_string(block.first_line);
    commands += static_cast<int>(lines.size());
    if (synopsis) {
      CheckSynopsis(lines, where);
    } else {
      for (const std::string& command : lines) RunExample(command, where);
    }
  }
  EXPECT_GT(commands, 0) << GetParam() << " shows no commands: is the extraction still right?";
}

INSTANTIATE_TEST_SUITE_P(Files, DocumentedReadmeCommands,
                         ::testing::Values("README.md", "programs/README.md", "bench/README.md"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
