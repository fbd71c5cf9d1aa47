#include <cstdio>
#include <string>

#include <fmt/format.h>

#include "vm/cli/commands.h"

namespace {

constexpr int kUsageError = 2;

// CLI11 reports `vs11 frobnicate` as "A subcommand is required": name the word it did not know.
std::string UsageMessage(const CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
    std::string known;
    for (const CLI::App* sub : app.get_subcommands({})) known += (known.empty() ? "" : ", ") + sub->get_name();
    return fmt::format("unknown subcommand '{}' (known: {})", argv[1], known);
  }
  return error.what();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vs11: assemble, validate, run, verify and count Direct3D vs_1_1 vertex shader programs"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vs11 0.1.0");
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "vs11: error: {}\nRun with --help for more information.\n", UsageMessage(app, e, argc, argv));
    return kUsageError;
  } catch (const vs11::cli::CommandFailure& failure) {
    return failure.exit_code;
  }
  return 0;
}
