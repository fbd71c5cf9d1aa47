#include <cstdio>
#include <new>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "vm/cli/commands.h"
#include "vm/cli/parse_command_line.h"
#include "vm/core/atomic_file.h"
#include "vm/core/leak_check.h"
#include "vm/core/version.h"
#include "vm/gl/gl_engine.h"

namespace {

// CLI11 reports `vs11 frobnicate` as "A subcommand is required": name the word it did not know.
std::string UsageMessage(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
    std::string known;
    for (const CLI::App* sub : app.get_subcommands({})) known += (known.empty() ? "" : ", ") + sub->get_name();
    return fmt::format("unknown subcommand '{}' (known: {})", argv[1], known);
  }
  return error.what();
}

int Main(int argc, char** argv) {
  vs11::gl::RegisterGlEngine();
  CLI::App app{"vs11: assemble, validate, run, verify, count and translate Direct3D vs_1_1 vertex shader programs"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("vs11 {}", vs11::Vs11Version()));
  app.footer("Exit status: 0 success, 1 bad input or a failed check, 2 a usage error.\n\n"
             "Examples:\n"
             "  vs11 validate programs/sh9_irradiance.vsh\n"
             "  vs11 asm --help");
  vs11::cli::AddAsmCommand(app);
  vs11::cli::AddDisasmCommand(app);
  vs11::cli::AddValidateCommand(app);
  vs11::cli::AddRunCommand(app);
  vs11::cli::AddCountCommand(app);
  vs11::cli::AddVerifyCommand(app);
  vs11::cli::AddTranslateCommand(app);
  try {
    auto usage = [&](const CLI::ParseError& e) { return UsageMessage(app, e, argc, argv); };
    if (std::optional<int> status = vs11::cli::ParseCommandLine(app, argc, argv, "vs11", usage)) return *status;
  } catch (const vs11::cli::CommandFailure& failure) {
    return failure.exit_code;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const vs11::EndOfMainLeakCheck leak_check;  // first: destroyed last, before the static objects
  vs11::RemoveTemporariesOnSignals();  // an interrupted run leaves no half-written file
  try {
    return Main(argc, argv);
  } catch (const std::bad_alloc&) {
    // An output file is written through a temporary, removed on the way here: nothing is left half written.
    std::fputs("vs11: error: out of memory (fewer vertices, or a larger memory limit, may help)\n", stderr);
    return 1;
  }
}
