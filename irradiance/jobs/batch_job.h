// `irrmap batch`: the nine SH coefficients and the seven constants of many environment files in
// one process, every core busy, one JSON Lines record per file.
//
// Inputs: paths, glob patterns (*, ?, [...]) and list files (one path or pattern per line, # starts
// a comment), expanded, de-duplicated (by InputKey: one file named two ways is one input) and
// sorted, so every run and every machine sees the same order; --shard K/N then keeps the inputs
// whose index i in that order has i % N == K.
//
// Output: one line per finished input, appended and flushed as soon as it is done (an interrupted
// run keeps every finished line):
//   {"input": PATH as given, "path": its InputKey (batch_output.h), "schema_version", "face_size",
//    "layout", "level", "level_size", "estimated_error", "error_metric" (what estimated_error and
//    --max-error measure), "order" (the program the level was chosen for), "coefficients": 9 x
//    [r, g, b] (L00, L1-1, ..., L22, windowed), "constants": {"cAr": [x, y, z, w], ...},
//    "convention", "provenance" (irradiance/jobs/output_metadata.h: the basis, frame and units; the
//    input's files with their SHA-256, vs11's version and every option that changes the numbers)}
// Each input is irrmap's own job (RunIrrmap, coefficients only), so a record holds the numbers
// `irrmap --coefficients-only` and vs11.irradiance.project() give with the options it lists.
// and optionally, per input, DIR/<input with '/' as '__'>.json holding the same record, written
// atomically; two inputs of one name there are refused before any work. A file that cannot be read
// or used is reported (its path and why) and skipped; the others go on. --resume keeps the records
// already in the output and skips their inputs, known by "path" (a last line cut off by an
// interruption is dropped first; a file that is not wholly records of this schema version, or that
// holds records of an older or newer one, is left untouched and refused).
// The output is locked for the run (OutputLock, "OUTPUT.lock"), and DIR for the run's shard: a
// second run into them ends at once, naming the first.
#pragma once

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "irradiance/io/option_names.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/sh/level_choice.h"
#include "vm/core/result.h"
#include "vm/core/thread_pool.h"

namespace vs11::irradiance {

inline constexpr ShOrder kDefaultBatchOrder = ShOrder::kOrder2;

struct BatchOptions {
  std::vector<std::string> inputs;  // paths or glob patterns
  std::vector<std::filesystem::path> list_files;
  std::filesystem::path output;       // the JSON Lines file
  std::filesystem::path per_file_dir;  // empty: no per-file outputs
  bool resume = false;
  int shard_index = 0;  // K of --shard K/N, 0 <= K < N
  int shard_count = 1;  // N
  int threads = 0;      // 0: every core; at most pool's threads run at once
  ThreadPool* pool = nullptr;  // the threads inputs run on; null: ThreadPool::Default()
  EnvironmentLayout layout = EnvironmentLayout::kAuto;
  int face_size = kDefaultFaceSize;  // angular maps are resampled to this; a lat-long map's levels take its grids
  std::optional<int> level;
  double max_error = kDefaultMaxLevelError;
  ErrorMetric error_metric = kDefaultErrorMetric;  // what max_error bounds, as irrmap's
  // As irrmap's --order, --window and --window-width. The order defaults to order2: the nine
  // coefficients are what a batch is for, and "auto" (nullopt) may pick a cheaper program at a coarser level.
  std::optional<ShOrder> order = kDefaultBatchOrder;
  ShWindow window = ShWindow::kNone;
  double window_width = kDefaultWindowWidth;
  // Set from another thread to stop early (the Python module's generator, closed): no input starts
  // after a worker sees it; the inputs already running finish and are written. Null: run them all.
  const std::atomic<bool>* stop = nullptr;
  OptionNaming naming = OptionNaming::kFlag;  // "--max-error 2" (the tool) or "max_error=2" (Python)
};

struct BatchFailure {
  std::string input;
  std::string reason;
};

struct BatchSummary {
  std::size_t selected = 0;  // inputs in this shard
  std::size_t resumed = 0;   // already in the output, skipped
  std::size_t succeeded = 0;
  std::vector<BatchFailure> failures;  // in input order
  double seconds = 0.0;
};

// Called after every finished input (done of total, where total excludes resumed inputs), from
// whichever worker finished it, one call at a time.
using BatchProgress = std::function<void(std::size_t done, std::size_t total)>;
// Called for every failed input as it fails, one call at a time.
using BatchFailureReport = std::function<void(const BatchFailure& failure)>;
// Called with every record's line (its JSON and the '\n') right after the line is written to the
// output, from whichever worker finished it, one call at a time (with the failure reports).
using BatchRecordReport = std::function<void(const std::string& line)>;

// Parses "K/N" (0 <= K < N); nullopt when it is not that.
std::optional<std::pair<int, int>> ParseShard(const std::string& text);

// Inputs and list files expanded, de-duplicated and sorted; an error when a list file cannot be
// read (kCannotReadFile) or a pattern or path matches nothing (kNoSuchInput; in a list file, its
// place is the list's file and line).
Result<std::vector<std::string>> ExpandBatchInputs(const std::vector<std::string>& inputs,
                                                   const std::vector<std::filesystem::path>& list_files);

// "OUT is the input IN: refusing to overwrite it" when -o is one of the inputs or list files (the
// same file, however spelled; kOutputOverwritesInput), checked before anything is read or written;
// else success.
Status BatchOutputOverwritesInput(const BatchOptions& options);

// The inputs with index % count == index_of_shard.
std::vector<std::string> ShardOf(const std::vector<std::string>& sorted_inputs, int index_of_shard, int count);

// The problem with the options themselves (a usage error: a bad value, no output or input given;
// kOptionValue or kFaceSize), or success; RunBatch checks them first too.
Status CheckBatchOptions(const BatchOptions& options);

// Runs the batch. Returns the error of a problem with the options or the output file (nothing
// processed); failures of single inputs go to summary.failures instead.
Status RunBatch(const BatchOptions& options, BatchSummary& summary, const BatchProgress& progress = {},
                const BatchFailureReport& report = {}, const BatchRecordReport& record = {});

}  // namespace vs11::irradiance
