// `irrmap batch`: coefficients and constants of many environment files in one process
// (irradiance/jobs/batch_job.h), with a progress line on stderr and a summary of the failures.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "irradiance/cli/subcommands.h"
#include "irradiance/jobs/batch_job.h"
#include "vm/cli/choice_option.h"

namespace vs11::irradiance::cli {
namespace {

constexpr int kBarWidth = 30;
// Without a terminal, a plain progress line at most this often.
constexpr double kPlainLineSeconds = 5.0;

struct BatchArguments {
  BatchOptions options;
  std::string shard = "0/1";
  int level = -1;
};

std::string FormatSeconds(double seconds) {
  if (seconds < 60.0) return fmt::format("{:.0f} s", seconds);
  if (seconds < 3600.0) {
    const int whole = static_cast<int>(seconds);
    return fmt::format("{} min {:02} s", whole / 60, whole % 60);
  }
  return fmt::format("{:.1f} h", seconds / 3600.0);
}

// Files per second and the time left, as a bar redrawn in place on a terminal, or as a plain line
// every kPlainLineSeconds (and at the end) otherwise.
BatchProgress MakeProgress() {
  const bool terminal = isatty(fileno(stderr)) != 0;
  const auto start = std::chrono::steady_clock::now();
  return [terminal, start, last_line = -kPlainLineSeconds](std::size_t done, std::size_t total) mutable {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
    const std::string left = rate > 0.0 ? FormatSeconds((total - done) / rate) : "?";
    const std::string numbers = fmt::format("{}/{} files, {:.1f} files/s, {} left", done, total, rate, left);
    if (terminal) {
      const int filled = total == 0 ? kBarWidth : static_cast<int>(kBarWidth * done / total);
      fmt::print(stderr, "\r\033[Kirrmap batch: [{}{}] {}", std::string(filled, '#'), std::string(kBarWidth - filled, ' '),
                 numbers);
      if (done == total) fmt::print(stderr, "\n");
    } else if (elapsed - last_line >= kPlainLineSeconds || done == total) {
      last_line = elapsed;
      fmt::print(stderr, "irrmap batch: {}\n", numbers);
    }
    std::fflush(stderr);
  };
}

void RunBatchCommand(BatchArguments& arguments) {
  BatchOptions& options = arguments.options;
  const std::optional<std::pair<int, int>> shard = ParseShard(arguments.shard);
  if (!shard) throw CLI::ValidationError("--shard", fmt::format("'{}' is not K/N with 0 <= K < N", arguments.shard));
  options.shard_index = shard->first;
  options.shard_count = shard->second;
  if (arguments.level >= 0) options.level = arguments.level;
  if (const Status usage = CheckBatchOptions(options); !usage.ok()) throw CLI::ValidationError(usage.message());
  if (const Status error = BatchOutputOverwritesInput(options); !error.ok()) {
    throw CLI::ValidationError("-o", error.message());
  }
  BatchSummary summary;
  const bool terminal = isatty(fileno(stderr)) != 0;
  auto report = [terminal](const BatchFailure& failure) {
    fmt::print(stderr, "{}irrmap batch: skipped {}: {}\n", terminal ? "\r\033[K" : "", failure.input, failure.reason);
  };
  if (const Status error = RunBatch(options, summary, MakeProgress(), report); !error.ok()) {
    throw SubcommandFailure(error.message());
  }
  const std::size_t processed = summary.succeeded + summary.failures.size();
  fmt::print("{} inputs in shard {}/{}: {} written to {}, {} already there (--resume), {} failed; {:.2f} s, {:.1f} files/s\n",
             summary.selected, options.shard_index, options.shard_count, summary.succeeded, options.output.string(),
             summary.resumed, summary.failures.size(), summary.seconds,
             summary.seconds > 0.0 ? processed / summary.seconds : 0.0);
  if (!summary.failures.empty()) {
    fmt::print("failed:\n");
    for (const BatchFailure& failure : summary.failures) fmt::print("  {}: {}\n", failure.input, failure.reason);
    throw SubcommandFailure(fmt::format("{} of {} inputs failed (listed above); the others are in {}",
                                        summary.failures.size(), processed, options.output.string()));
  }
}

}  // namespace

void AddBatchCommand(CLI::App& app) {
  auto arguments = std::make_shared<BatchArguments>();
  CLI::App* batch = app.add_subcommand(
      "batch",
      "Coefficients and constants of many environment files in one process, every core busy: one JSON\n"
      "line per file in -o FILE, written and flushed as each file finishes.");
  batch->footer(
      "Each line: {\"input\", \"path\", \"schema_version\", \"face_size\", \"layout\", \"level\",\n"
      "\"level_size\", \"estimated_error\", \"error_metric\", \"order\", \"coefficients\" (9 x [r, g, b]:\n"
      "L00, L1-1, L10, L11, L2-2, L2-1, L20, L21, L22), \"constants\" (cAr cAg cAb cBr cBg cBb cC as\n"
      "[x, y, z, w]), \"convention\" (basis, frame, radiance, units), \"provenance\" (the files read with\n"
      "their size and SHA-256, vs11's version, every option that changes the numbers)}. Each file is\n"
      "irrmap --coefficients-only's job with these options; the level is picked as by irrmap --max-error\n"
      "for --order (default order2) unless --level is given. A file that cannot be read or used is reported on stderr with the\n"
      "reason and skipped; the exit status is then 1 and the summary lists every such file.\n"
      "Inputs are expanded (globs), de-duplicated and sorted; --shard K/N keeps every N-th from the\n"
      "K-th (K from 0), so N machines given the same inputs split them with no coordinator.\n"
      "--resume keeps the lines already in -o FILE and skips their inputs, known by their canonical\n"
      "path (an interrupted run loses nothing; a half-written last line is dropped); a FILE that is not\n"
      "wholly irrmap batch's records of this vs11's schema version is refused and left as it is; without --resume an existing -o FILE\n"
      "is an error. -o FILE is locked for the run (FILE.lock says by whom), and --per-file DIR for the\n"
      "run's shard: a second run into them ends at once, naming the first; the lock of a run that died\n"
      "is free. Two inputs that --per-file would give one name (x/y.exr, x__y.exr) are refused.\n"
      "Progress (files/s, time left) goes to stderr: a bar on a terminal, otherwise a line every 5 s.\n"
      "Exit status: 0 success, 1 an input failed (the others are written) or -o FILE or --per-file DIR\n"
      "cannot be used, 2 a usage error (an unknown option, a bad option value; before any work).\n"
      "\n"
      "Examples:\n"
      "  irrmap batch 'panoramas/*.exr' -o sh.jsonl\n"
      "  irrmap batch --list files.txt -o sh.jsonl --per-file sh/ --layout latlong --face-size 128\n"
      "  irrmap batch 'data/*/*.hdr' -o part-3.jsonl --shard 3/16 --resume\n");
  batch->add_option("INPUT", arguments->options.inputs, "environment files or glob patterns (quote them)");
  batch->add_option("--list", arguments->options.list_files,
                    "a file of inputs, one path or pattern per line (# comments); may repeat")
      ->check(CLI::ExistingFile);
  batch->add_option("-o,--output", arguments->options.output, "the JSON Lines file")->required();
  batch->add_option("--per-file", arguments->options.per_file_dir,
                    "also write each file's record as DIR/<input path with / as __>.json (atomically)");
  batch->add_flag("--resume", arguments->options.resume, "continue an existing output, skipping inputs it holds");
  batch->add_option("--shard", arguments->shard, "K/N: process the K-th of N slices (K from 0)")->capture_default_str();
  batch->add_option("--threads", arguments->options.threads, "files processed at once (0 = every core)")
      ->capture_default_str();
  vs11::cli::AddChoiceOption(*batch, "--layout", arguments->options.layout, kLayoutNames,
                              "layout of every file (as irrmap's --layout)");
  batch->add_option("--face-size", arguments->options.face_size,
                    "face size of cubes resampled from angular maps, and the cube whose grids a latlong map's levels take (it is projected where it lies); a power of two")
      ->capture_default_str();
  CLI::Option* level = batch->add_option("--level", arguments->level, "mip level of every file (default: by --max-error)")
                          ->check(CLI::NonNegativeNumber);
  batch->add_option("--max-error", arguments->options.max_error,
                    "pick the coarsest level whose estimated error stays under this fraction")
      ->capture_default_str()
      ->excludes(level);
  vs11::cli::AddChoiceOption(*batch, "--error-metric", arguments->options.error_metric, kErrorMetricNames,
                              fmt::format("what --max-error measures, as irrmap's: {}", kErrorMetricNames.List()));
  vs11::cli::AddChoiceOption(*batch, "--order", arguments->options.order, kShOrderNames, kAutoOrderName,
                              fmt::format("the program the level is chosen for, as irrmap's: {}",
                                          kShOrderNames.List(kAutoOrderName)));
  vs11::cli::AddChoiceOption(*batch, "--window", arguments->options.window, kShWindowNames,
                              fmt::format("window applied to the coefficients, as irrmap's: {}", kShWindowNames.List()));
  batch->add_option("--window-width", arguments->options.window_width, "bands, for hanning and lanczos")
      ->capture_default_str();
  batch->callback([arguments] { RunBatchCommand(*arguments); });
}

}  // namespace vs11::irradiance::cli
