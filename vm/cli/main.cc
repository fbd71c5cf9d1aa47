#include <cstdio>

#include "vm/cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"vs11: assemble, validate, run, verify and count Direct3D vs_1_1 vertex shader programs"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "vs11 0.1.0");
  vs11::cli::AddAsmCommand(app);
  vs11::cli::AddDisasmCommand(app);
  vs11::cli::AddValidateCommand(app);
  vs11::cli::AddRunCommand(app);
  vs11::cli::AddCountCommand(app);
  vs11::cli::AddVerifyCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const vs11::cli::CommandFailure& failure) {
    return failure.exit_code;
  }
  return 0;
}
