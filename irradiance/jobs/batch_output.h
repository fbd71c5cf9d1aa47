// irrmap batch's outputs (batch_job.h): the JSON Lines file, opened under an exclusive lock and, on
// --resume, checked line by line to be wholly irrmap batch's own before anything in it changes; the
// identity of an input; and the --per-file names, checked to be unique before any work.
#pragma once

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "irradiance/jobs/output_lock.h"

namespace vs11::irradiance {

// The identity of an input, its record's "path": the canonical path of its folder (absolute,
// symbolic links and "." and ".." resolved) and its own name. So `a.exr`, `./a.exr` and
// `/data/a.exr` run in /data are one input, while links to one file stay separate inputs, as copies
// of it would be.
std::string InputKey(const std::string& input);

// The input key of a record: its "path", or, in a record of a version that wrote none, InputKey of
// its "input"; nullopt when `record` is not a record of irrmap batch.
std::optional<std::string> RecordKey(const nlohmann::json& record);

// The JSON Lines output of a batch, open for appending and locked (OutputLock on "OUTPUT.lock")
// for as long as this lives.
class BatchOutput {
 public:
  // Refuses an output that is not a regular file, takes the lock, and opens an existing output, only
  // with `resume`, and only once every line was checked to be a record (a last line without its
  // newline must be the start of one, and is then cut off: a run stopped while writing it). Nothing
  // in the file changes unless every line passed. Returns why not, with file:line.
  Status Open(const std::filesystem::path& path, bool resume);
  // Creates the output if Open found none: once the run is sure to start, so that a run refused
  // before any work leaves no empty output behind.
  Status BeginWriting();
  // The keys of the records the file held when opened.
  const std::set<std::string>& completed() const { return completed_; }
  // Appends `line` and flushes it; false when that failed.
  bool Append(const std::string& line);

 private:
  Status ReadRecords(int fd, const std::filesystem::path& path);

  std::optional<OutputLock> lock_;
  std::filesystem::path path_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_{nullptr, &std::fclose};
  std::set<std::string> completed_;
};

// The --per-file name of `input`: its path with separators as "__" ("./" dropped) and ".json".
std::string PerFileName(std::string input);

// Checked before any work: that no two of `inputs` (every shard's) get one --per-file name (x/y.pfm
// and x__y.pfm), and that no file in `folder` named for one of `todo` holds another input's record or
// something that is not a record (kPerFileCollision, kBatchRecord).
Status CheckPerFileNames(const std::filesystem::path& folder, const std::vector<std::string>& inputs,
                         const std::vector<std::string>& todo);

}  // namespace vs11::irradiance
