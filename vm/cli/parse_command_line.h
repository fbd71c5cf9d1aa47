// The command-line parse both tools (vs11 and irrmap) end their set-up with: help and version print
// and end the program with status 0, a usage error prints "TOOL: error: ..." and ends it with status 2.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace vs11::cli {

inline constexpr int kUsageErrorStatus = 2;

// Parses argv into `app`. Returns the status the program ends with when parsing ends it (help,
// version, a usage error), nullopt when the work goes on. `usage_message` words a usage error
// (default: CLI11's own). Exceptions from option and subcommand callbacks pass through.
template <class UsageMessage>
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, std::string_view tool,
                                    UsageMessage usage_message) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    fmt::print(stderr, "{}: error: {}\nRun with --help for more information.\n", tool, usage_message(e));
    return kUsageErrorStatus;
  }
  return std::nullopt;
}

inline std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, std::string_view tool) {
  return ParseCommandLine(app, argc, argv, tool, [](const CLI::ParseError& e) { return std::string(e.what()); });
}

}  // namespace vs11::cli
