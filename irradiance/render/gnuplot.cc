#include "irradiance/render/gnuplot.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// The font the preview uses too (fonts-dejavu-core); cairo falls back to another if it is missing.
constexpr const char* kFont = "DejaVu Sans,11";

struct TemporaryFiles {
  std::vector<fs::path> paths;
  ~TemporaryFiles() {
    for (const fs::path& path : paths) RemoveQuietly(path);
  }
};

fs::path TemporaryBeside(const fs::path& path, TemporaryFiles& temporaries) {
  fs::path temporary = TemporaryPathBeside(path);
  temporaries.paths.push_back(temporary);
  return temporary;
}

std::optional<std::string> TerminalFor(const fs::path& output, const GnuplotChart& chart) {
  const std::string extension = output.extension().string();
  if (extension == ".svg") {
    return fmt::format("set terminal svg size {},{} dynamic font '{}' background rgb 'white'", chart.width,
                       chart.height, kFont);
  }
  if (extension == ".png") {
    return fmt::format("set terminal pngcairo size {},{} font '{}' background rgb 'white'", chart.width,
                       chart.height, kFont);
  }
  return std::nullopt;
}

// Runs `gnuplot script` with stdout and stderr going to `log`; the exit status, or -1 when gnuplot
// could not be started.
int RunGnuplot(const fs::path& script, const fs::path& log) {
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    const int null_input = open("/dev/null", O_RDONLY);
    if (null_input >= 0) dup2(null_input, STDIN_FILENO);
    execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string GnuplotQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) {
    quoted += c;
    if (c == '\'') quoted += '\'';  // gnuplot doubles a quote inside single quotes
  }
  return quoted + "'";
}

std::string GnuplotLiteral(const std::string& text) {
  // Inside single quotes a backslash reaches the enhanced-text parser as it is, which then takes
  // the next character literally.
  constexpr std::string_view kEnhancedMarkup = "_^@&~{}\\";
  std::string escaped;
  for (char c : text) {
    if (kEnhancedMarkup.find(c) != std::string_view::npos) escaped += '\\';
    escaped += c;
  }
  return GnuplotQuote(escaped);
}

Status RenderGnuplotChart(const GnuplotChart& chart, const std::vector<fs::path>& outputs) {
  if (outputs.empty()) return {};
  TemporaryFiles temporaries;
  const fs::path& first = outputs.front();
  const fs::path data = TemporaryBeside(first.parent_path() / "chart.dat", temporaries);
  const fs::path script = TemporaryBeside(first.parent_path() / "chart.gp", temporaries);
  const fs::path log = TemporaryBeside(first.parent_path() / "gnuplot.log", temporaries);
  if (Status written = WriteFileAtomically(data, chart.data); !written) return written;

  std::ostringstream commands;
  std::vector<fs::path> images;
  for (const fs::path& output : outputs) {
    const std::optional<std::string> terminal = TerminalFor(output, chart);
    if (!terminal) {
      return Failure(DiagnosticCode::kGnuplot,
                     fmt::format("cannot plot {}: the chart's file must end in .svg or .png", output.string()));
    }
    images.push_back(TemporaryBeside(output, temporaries));
    commands << "reset session\n" << *terminal << "\nset output " << GnuplotQuote(images.back().string()) << "\n"
             << "datafile = " << GnuplotQuote(data.string()) << "\n"
             // Tick labels as numbers read (10000, 0.001, 1e-05), not gnuplot's log-axis default
             // 10000.000000; a chart's script can still set its own.
             << "set format x '%g'\nset format y '%g'\n"
             << chart.script << "\nunset output\n";
  }
  if (Status written = WriteFileAtomically(script, commands.str()); !written) return written;

  const int status = RunGnuplot(script, log);
  if (status != 0) {
    std::ifstream log_stream(log);
    std::string message((std::istreambuf_iterator<char>(log_stream)), std::istreambuf_iterator<char>());
    if (status == 127 || status < 0) {
      return Failure(DiagnosticCode::kGnuplot, "cannot run gnuplot (install Debian's gnuplot-nox, as .ci/setup does)");
    }
    return Failure(DiagnosticCode::kGnuplot, fmt::format("gnuplot failed (exit status {}): {}", status, message));
  }
  for (std::size_t i = 0; i < images.size(); ++i) {
    std::error_code ec;
    if (!fs::exists(images[i], ec) || fs::file_size(images[i], ec) == 0) {
      return Failure(DiagnosticCode::kGnuplot, fmt::format("gnuplot wrote no image for {}", outputs[i].string()));
    }
  }
  std::vector<PendingRename> renames;
  for (std::size_t i = 0; i < images.size(); ++i) renames.push_back({images[i], outputs[i]});
  return CommitRenames(renames);
}

}  // namespace vs11::irradiance
