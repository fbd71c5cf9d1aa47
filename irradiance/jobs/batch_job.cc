// `irrmap batch`. See batch_job.h.
#include "irradiance/jobs/batch_job.h"

#include <glob.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <sstream>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/jobs/batch_output.h"
#include "irradiance/jobs/irrmap_checks.h"
#include "irradiance/jobs/irrmap_job.h"
#include "irradiance/jobs/output_metadata.h"
#include "irradiance/sh/constants_output.h"
#include "irradiance/sh/sh_projection.h"
#include "vm/asm/program_file.h"
#include "vm/core/atomic_file.h"
#include "vm/core/input_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

bool IsPattern(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

// Appends the paths `pattern` matches (glob(3), sorted), or the path itself when it is no pattern;
// kNoSuchInput when a pattern matches nothing.
Status AddExpanded(const std::string& input, std::vector<std::string>& out) {
  if (!IsPattern(input)) {
    out.push_back(input);  // a missing file is reported as that file's failure
    return {};
  }
  glob_t matches{};
  const int status = glob(input.c_str(), GLOB_ERR, nullptr, &matches);
  if (status == 0) {
    for (std::size_t i = 0; i < matches.gl_pathc; ++i) out.emplace_back(matches.gl_pathv[i]);
  }
  globfree(&matches);
  if (status == GLOB_NOMATCH) {
    return Failure(DiagnosticCode::kNoSuchInput, fmt::format("pattern '{}' matches no file", input));
  }
  if (status != 0) {
    return Failure(DiagnosticCode::kNoSuchInput,
                   fmt::format("pattern '{}' cannot be expanded (a folder cannot be read)", input));
  }
  return {};
}

std::string Trimmed(const std::string& line) {
  const std::size_t first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
}

// Basis pyramids by face size, each built once, by the first worker that needs it.
class BasisCache {
 public:
  std::shared_ptr<const BasisPyramid> Get(int face_size) {
    std::lock_guard lock(mutex_);
    std::shared_ptr<const BasisPyramid>& slot = pyramids_[face_size];
    if (!slot) {
      std::optional<BasisPyramid> built = BuildBasisPyramid(face_size);
      if (built) slot = std::make_shared<const BasisPyramid>(std::move(*built));
    }
    return slot;
  }

 private:
  std::mutex mutex_;
  std::map<int, std::shared_ptr<const BasisPyramid>> pyramids_;
};

// One input's job: irrmap's own (RunIrrmap with coefficients only), so that a record holds exactly
// what `irrmap --coefficients-only` and the Python module's project() give for the same options.
IrrmapOptions InputOptions(const BatchOptions& options, BasisCache& basis, const std::string& input) {
  IrrmapOptions job;
  job.environment = input;
  job.layout = options.layout;
  job.face_size = options.face_size;
  job.level = options.level;
  job.max_error = options.max_error;
  job.error_metric = options.error_metric;
  job.order = options.order;
  job.window = options.window;
  job.window_width = options.window_width;
  job.threads = 1;  // the inputs run in parallel instead
  job.coefficients_only = true;
  job.write_files = false;
  job.naming = options.naming;
  job.shared_basis = [&basis](int face_size) { return basis.Get(face_size); };
  return job;
}

// The record of one input, or the reason it has none (batch_job.h lists its fields).
Status ProcessInput(const BatchOptions& options, BasisCache& basis, const std::string& input,
                    nlohmann::ordered_json& record) {
  const IrrmapOptions job = InputOptions(options, basis, input);
  IrrmapReport report;
  if (Status ran = RunIrrmap(job, report); !ran.ok()) {
    const std::string prefix = input + ": ";  // the failure report names the input already
    const std::string& message = ran.error().message;
    if (!message.starts_with(prefix)) return ran;
    return Failure(ran.error().code, message.substr(prefix.size()), ran.error().loc);
  }
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::array();
  for (const glm::dvec3& c : report.coefficients.coefficients) coefficients.push_back({c.r, c.g, c.b});
  nlohmann::ordered_json metadata = OutputMetadata(report, job);
  record = {{"input", input},
            {"path", InputKey(input)},
            {"schema_version", metadata["schema_version"]},
            {"face_size", report.face_size},
            {"layout", report.layout},
            {"level", report.level},
            {"level_size", report.levels[report.level].size},
            {"estimated_error", report.levels[report.level].estimated_error},
            {"error_metric", std::string(ErrorMetricName(report.error_metric))},
            {"order", std::string(ShOrderName(report.order))},
            {"coefficients", std::move(coefficients)},
            {"constants", ConstantsJson(report.constants)},
            {"convention", std::move(metadata["convention"])},
            {"provenance", std::move(metadata["provenance"])}};
  return {};
}

// The options of every input's job (irrmap's own checks), then the batch's.
Status CheckOptions(const BatchOptions& options) {
  BasisCache unused;
  CheckedOptions checked;
  if (Status error = CheckOptionValues(InputOptions(options, unused, "each input"), checked); !error.ok()) return error;
  const auto usage = [](std::string message) { return Failure(DiagnosticCode::kOptionValue, std::move(message)); };
  if (options.shard_count < 1 || options.shard_index < 0 || options.shard_index >= options.shard_count) {
    return usage(
        fmt::format("--shard {}/{} is out of range: K/N with 0 <= K < N", options.shard_index, options.shard_count));
  }
  if (options.threads < 0) {
    return usage(fmt::format("{} must be >= 0 (0: every core)",
                             OptionWithValue(OptionName(options.naming, "threads"), options.threads)));
  }
  if (options.output.empty()) return usage("no output file given (-o FILE.jsonl)");
  if (options.inputs.empty() && options.list_files.empty()) return usage("no input files given");
  return {};
}

// The lock of a --per-file folder, one per shard: shards of one input list write disjoint names
// (CheckPerFileNames), so they may share the folder; two runs of one shard may not.
fs::path PerFileLock(const BatchOptions& options) {
  return options.per_file_dir /
         fmt::format(".irrmap-batch-shard-{}-of-{}.lock", options.shard_index, options.shard_count);
}

}  // namespace

Status CheckBatchOptions(const BatchOptions& options) { return CheckOptions(options); }

std::optional<std::pair<int, int>> ParseShard(const std::string& text) {
  int index = 0, count = 0;
  char slash = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> index >> slash >> count) || slash != '/' || (in >> extra)) return std::nullopt;
  if (count < 1 || index < 0 || index >= count) return std::nullopt;
  return std::pair{index, count};
}

Status BatchOutputOverwritesInput(const BatchOptions& options) {
  std::vector<fs::path> inputs(options.list_files.begin(), options.list_files.end());
  // A list that cannot be read is reported by RunBatch.
  if (Result<std::vector<std::string>> expanded = ExpandBatchInputs(options.inputs, options.list_files)) {
    inputs.insert(inputs.end(), expanded->begin(), expanded->end());
  }
  return OutputOverwritesInput(options.output, inputs);
}

Result<std::vector<std::string>> ExpandBatchInputs(const std::vector<std::string>& inputs,
                                                   const std::vector<fs::path>& list_files) {
  std::vector<std::string> out;
  for (const std::string& input : inputs) {
    if (const Status problem = AddExpanded(input, out); !problem.ok()) return problem.error();
  }
  for (const fs::path& list : list_files) {
    const auto unreadable = [&list] {
      return Failure(DiagnosticCode::kCannotReadFile, fmt::format("cannot read the list file {}", list.string()));
    };
    std::ifstream in(list);
    if (!in) return unreadable();
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      const std::string entry = Trimmed(line);
      if (entry.empty() || entry.starts_with('#')) continue;
      if (const Status problem = AddExpanded(entry, out); !problem.ok()) {
        return Failure(problem.error().code, fmt::format("{}:{}: {}", list.string(), number, problem.message()),
                       {list.string(), number});
      }
    }
    if (in.bad()) return unreadable();
  }
  std::sort(out.begin(), out.end());
  std::set<std::string> keys;
  std::erase_if(out, [&keys](const std::string& input) { return !keys.insert(InputKey(input)).second; });
  return out;
}

std::vector<std::string> ShardOf(const std::vector<std::string>& sorted_inputs, int index_of_shard, int count) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < sorted_inputs.size(); ++i) {
    if (static_cast<int>(i % count) == index_of_shard) out.push_back(sorted_inputs[i]);
  }
  return out;
}

Status RunBatch(const BatchOptions& options, BatchSummary& summary, const BatchProgress& progress,
                const BatchFailureReport& report, const BatchRecordReport& record) {
  const auto start = std::chrono::steady_clock::now();
  summary = BatchSummary{};
  if (Status error = CheckOptions(options); !error.ok()) return error;
  if (Status error = BatchOutputOverwritesInput(options); !error.ok()) return error;
  const Result<std::vector<std::string>> expanded = ExpandBatchInputs(options.inputs, options.list_files);
  if (!expanded) return expanded.error();
  const std::vector<std::string>& all = *expanded;
  if (all.empty()) return Failure(DiagnosticCode::kNoSuchInput, "no input files given");
  const std::vector<std::string> shard = ShardOf(all, options.shard_index, options.shard_count);
  summary.selected = shard.size();
  const bool per_file = !options.per_file_dir.empty();
  if (per_file) {
    if (Status collision = CheckPerFileNames(options.per_file_dir, all, {}); !collision.ok()) return collision;
  }
  BatchOutput out;
  if (Status problem = out.Open(options.output, options.resume); !problem.ok()) return problem;
  std::vector<std::string> todo;
  for (const std::string& input : shard) {
    if (out.completed().count(InputKey(input)) == 0) todo.push_back(input);
  }
  summary.resumed = shard.size() - todo.size();
  std::optional<OutputLock> per_file_lock;
  if (per_file) {
    std::error_code ec;
    fs::create_directories(options.per_file_dir, ec);
    if (ec) {
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot create {} ({})", options.per_file_dir.string(), ec.message()));
    }
    Result<OutputLock> lock = OutputLock::Take(PerFileLock(options), options.per_file_dir.string());
    if (!lock) return lock.error();
    per_file_lock = std::move(lock).value();
    if (Status overwrite = CheckPerFileNames(options.per_file_dir, {}, todo); !overwrite.ok()) return overwrite;
  }
  if (Status problem = out.BeginWriting(); !problem.ok()) return problem;

  BasisCache basis;
  std::mutex mutex;  // guards `out`, `summary`, the callbacks and `failures`
  std::vector<std::pair<std::size_t, BatchFailure>> failures;
  std::atomic<std::size_t> next = 0;
  std::size_t finished = 0;
  Status write_error;
  auto work = [&] {
    for (std::size_t i = next++; i < todo.size(); i = next++) {
      if (options.stop != nullptr && options.stop->load()) break;
      nlohmann::ordered_json json;
      std::optional<std::string> reason;  // why this input has no record
      if (const Status processed = ProcessInput(options, basis, todo[i], json); !processed.ok()) {
        reason = processed.message();
      }
      std::string line;
      if (!reason) {
        line = json.dump() + "\n";
        if (per_file) {
          const fs::path path = options.per_file_dir / PerFileName(todo[i]);
          if (const Status written = WriteFileAtomically(path, json.dump(2) + "\n"); !written) {
            reason = fmt::format("cannot write {}: {}", path.string(), written.message());
          }
        }
      }
      std::lock_guard lock(mutex);
      if (reason) {
        failures.push_back({i, {todo[i], *reason}});
        if (report) report(failures.back().second);
      } else if (!out.Append(line)) {
        write_error =
            Failure(DiagnosticCode::kCannotWriteFile, fmt::format("cannot write to {}", options.output.string()));
        next = todo.size();  // stop: nothing more can be kept
      } else {
        ++summary.succeeded;
        if (record) record(line);
      }
      ++finished;
      if (progress) progress(finished, todo.size());
    }
  };
  // The inputs go to the pool's threads (the resampler's parallel calls nest in the same pool), so
  // the process never runs more of them at once than the pool has, whatever --threads asks for.
  ThreadPool& pool = options.pool != nullptr ? *options.pool : ThreadPool::Default();
  const int threads = options.threads > 0 ? options.threads : pool.threads();
  pool.Run(std::min<std::size_t>(todo.size(), static_cast<std::size_t>(threads)), threads,
           [&work](std::size_t, int) { work(); });
  std::sort(failures.begin(), failures.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [index, failure] : failures) summary.failures.push_back(std::move(failure));
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return write_error;
}

}  // namespace vs11::irradiance
