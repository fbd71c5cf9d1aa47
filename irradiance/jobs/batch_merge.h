// `irrmap batch-merge`: the outputs of the shards of one dataset (irrmap batch --shard K/N, or
// vs11.dask's parts) checked against the inputs the shards were given, and joined into one file.
//
// Every input (the same paths, patterns and list files as the shards', expanded as irrmap batch
// expands them) must have exactly one record across the parts, matched by the record's "path" (its
// InputKey, batch_output.h; so the merge runs where the inputs have the paths the shards saw). What is
// missing, what is there more than once (with each part:line) and records of no input are reported;
// only when there is none of these is the output written: every record's line as the shard wrote it,
// sorted by "path", through a temporary renamed into place (never a partial file). Extra fields in a
// record are kept as they are. A part line that is not a record is an error naming part:line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "vm/core/result.h"

namespace vs11::irradiance {

struct MergeOptions {
  std::vector<std::string> inputs;  // paths or glob patterns, as irrmap batch's
  std::vector<std::filesystem::path> list_files;
  std::vector<std::string> parts;  // the shards' JSON Lines files: paths or glob patterns
  std::filesystem::path output;    // empty: check only
};

struct MergeReport {
  struct Duplicate {
    std::string path;                     // the record's "path"
    std::vector<std::string> locations;   // PART:LINE of each record of it
  };
  struct Unexpected {
    std::string path;
    std::string location;  // PART:LINE
  };
  std::size_t inputs = 0;
  std::size_t parts = 0;
  std::size_t records = 0;
  std::vector<std::string> missing;  // inputs (as expanded) with no record, in input order
  std::vector<Duplicate> duplicated;  // by path
  std::vector<Unexpected> unexpected;  // records of no input, by path
  bool written = false;  // the output was written

  bool complete() const { return missing.empty() && duplicated.empty() && unexpected.empty(); }
};

// Checks the parts against the inputs, filling `report`, and writes the output when complete().
// Returns the error when the check could not be made (a pattern that matches nothing, an unreadable
// part, a line that is not a record, an output that is an input or a part, a failed write).
Status MergeBatchOutputs(const MergeOptions& options, MergeReport& report);

// The report as irrmap batch-merge --json prints it: inputs, parts, records, missing, duplicated
// ([{"path", "in": [PART:LINE...]}]), unexpected ([{"path", "in"}]), complete, output (null when
// nothing was written).
nlohmann::ordered_json MergeReportJson(const MergeReport& report, const std::filesystem::path& output);

}  // namespace vs11::irradiance
