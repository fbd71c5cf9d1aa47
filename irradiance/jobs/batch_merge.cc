// `irrmap batch-merge`. See batch_merge.h.
#include "irradiance/jobs/batch_merge.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>

#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/batch_output.h"
#include "vm/core/atomic_file.h"
#include "vm/core/input_file.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// A record is about 1.5 KB beside its two paths; a longer line is not one (as batch_output.cc).
constexpr std::size_t kMaxRecordBytes = 64 * 1024;

// Where a record's line is, to be copied into the output as it is.
struct RecordLine {
  std::string key;
  std::size_t part = 0;  // index into the parts
  std::size_t line = 0;  // from 1
  std::streamoff offset = 0;
  std::size_t length = 0;  // without the '\n'
};

std::string Location(const std::vector<std::string>& parts, const RecordLine& record) {
  return fmt::format("{}:{}", parts[record.part], record.line);
}

// Appends the records of `parts[index]`, or says which line is not one.
Status ReadPart(const std::vector<std::string>& parts, std::size_t index, std::vector<RecordLine>& records) {
  const std::string& part = parts[index];
  std::error_code ec;
  if (!fs::is_regular_file(part, ec)) {
    return Failure(DiagnosticCode::kCannotReadFile, fmt::format("{}: not a file (a part to merge)", part));
  }
  const auto unreadable = [&part] {
    return Failure(DiagnosticCode::kCannotReadFile, fmt::format("cannot read {}", part));
  };
  std::ifstream in(part, std::ios::binary);
  if (!in) return unreadable();
  std::string text;
  std::streamoff offset = 0;
  for (std::size_t number = 1; std::getline(in, text); ++number) {
    const bool cut_off = in.eof();  // no '\n' after it: the shard stopped while writing it
    const std::streamoff start = offset;
    offset += static_cast<std::streamoff>(text.size()) + 1;
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::optional<std::string> key;
    if (text.size() <= kMaxRecordBytes) key = RecordKey(nlohmann::json::parse(text, nullptr, false));
    if (!key) {
      return Failure(DiagnosticCode::kBatchRecord,
                     fmt::format("{}:{}: not a record of irrmap batch{}", part, number,
                                 cut_off ? " (cut off: that shard was interrupted; run it again with --resume)" : ""),
                     {part, static_cast<int>(number)});
    }
    records.push_back({*key, index, number, start, text.size()});
  }
  if (in.bad()) return unreadable();
  return {};
}

// The records' lines in `records`' order into `output`, through a temporary.
Status WriteMerged(const std::vector<std::string>& parts, const std::vector<RecordLine>& records,
                   const fs::path& output) {
  const fs::path temporary = TemporaryPathBeside(output);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    std::vector<std::ifstream> sources;
    for (const std::string& part : parts) sources.emplace_back(part, std::ios::binary);
    std::string line;
    for (const RecordLine& record : records) {
      std::ifstream& source = sources[record.part];
      line.resize(record.length);
      source.seekg(record.offset);
      if (!source.read(line.data(), static_cast<std::streamsize>(line.size()))) {
        RemoveQuietly(temporary);
        return Failure(DiagnosticCode::kCannotReadFile,
                       fmt::format("cannot read {} again (did it change during the merge?)", Location(parts, record)));
      }
      out << line << '\n';
    }
    out.flush();
    if (!out) {
      out.close();
      RemoveQuietly(temporary);
      return Failure(DiagnosticCode::kCannotWriteFile,
                     fmt::format("cannot write {} (a full disk, or a folder that cannot be written)", output.string()));
    }
  }
  const PendingRename rename{temporary, output};
  return CommitRenames({&rename, 1});
}

}  // namespace

Status MergeBatchOutputs(const MergeOptions& options, MergeReport& report) {
  report = MergeReport{};
  if (options.parts.empty()) return Failure(DiagnosticCode::kOptionValue, "no parts given (--parts FILE.jsonl...)");
  if (options.inputs.empty() && options.list_files.empty()) {
    return Failure(DiagnosticCode::kOptionValue, "no inputs given");
  }
  const Result<std::vector<std::string>> expanded_inputs = ExpandBatchInputs(options.inputs, options.list_files);
  if (!expanded_inputs) return expanded_inputs.error();
  const std::vector<std::string>& inputs = *expanded_inputs;
  const Result<std::vector<std::string>> expanded_parts = ExpandBatchInputs(options.parts, {});
  if (!expanded_parts) {
    return Failure(expanded_parts.error().code, fmt::format("--parts: {}", expanded_parts.message()),
                   expanded_parts.error().loc);
  }
  const std::vector<std::string>& parts = *expanded_parts;
  if (!options.output.empty()) {
    std::vector<fs::path> read(options.list_files);
    read.insert(read.end(), parts.begin(), parts.end());
    read.insert(read.end(), inputs.begin(), inputs.end());
    if (Status overwrite = OutputOverwritesInput(options.output, read); !overwrite.ok()) return overwrite;
  }
  report.inputs = inputs.size();
  report.parts = parts.size();

  std::vector<RecordLine> records;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (Status problem = ReadPart(parts, i, records); !problem.ok()) return problem;
  }
  report.records = records.size();
  std::stable_sort(records.begin(), records.end(),
                   [](const RecordLine& a, const RecordLine& b) { return a.key < b.key; });
  std::set<std::string> found;
  for (std::size_t i = 0; i < records.size();) {
    std::size_t end = i + 1;
    while (end < records.size() && records[end].key == records[i].key) ++end;
    found.insert(records[i].key);
    if (end - i > 1) {
      MergeReport::Duplicate duplicate{records[i].key, {}};
      for (std::size_t j = i; j < end; ++j) duplicate.locations.push_back(Location(parts, records[j]));
      report.duplicated.push_back(std::move(duplicate));
    }
    i = end;
  }
  std::set<std::string> expected;
  for (const std::string& input : inputs) {
    std::string key = InputKey(input);
    if (found.count(key) == 0) report.missing.push_back(input);
    expected.insert(std::move(key));
  }
  for (const RecordLine& record : records) {
    if (expected.count(record.key) == 0) report.unexpected.push_back({record.key, Location(parts, record)});
  }
  if (!report.complete() || options.output.empty()) return {};
  if (Status problem = WriteMerged(parts, records, options.output); !problem.ok()) return problem;
  report.written = true;
  return {};
}

nlohmann::ordered_json MergeReportJson(const MergeReport& report, const fs::path& output) {
  nlohmann::ordered_json duplicated = nlohmann::ordered_json::array();
  for (const MergeReport::Duplicate& duplicate : report.duplicated) {
    duplicated.push_back({{"path", duplicate.path}, {"in", duplicate.locations}});
  }
  nlohmann::ordered_json unexpected = nlohmann::ordered_json::array();
  for (const MergeReport::Unexpected& record : report.unexpected) {
    unexpected.push_back({{"path", record.path}, {"in", record.location}});
  }
  return {{"inputs", report.inputs},
          {"parts", report.parts},
          {"records", report.records},
          {"missing", report.missing},
          {"duplicated", std::move(duplicated)},
          {"unexpected", std::move(unexpected)},
          {"complete", report.complete()},
          {"output", report.written ? nlohmann::ordered_json(output.string()) : nlohmann::ordered_json(nullptr)}};
}

}  // namespace vs11::irradiance
