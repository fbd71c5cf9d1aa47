// irrmap batch's outputs. See batch_output.h.
#include "irradiance/jobs/batch_output.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <string_view>

#include <fmt/format.h>

#include "irradiance/jobs/output_metadata.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

// A record is about 1.5 KB beside its two paths (each at most PATH_MAX): a longer line is not one,
// and a file of one endless line (a device, a binary file) is never read into memory whole.
constexpr std::size_t kMaxRecordBytes = 64 * 1024;
constexpr std::size_t kReadChunkBytes = 64 * 1024;
// How every record's line starts (RunBatch dumps an ordered JSON object with "input" first, no spaces).
constexpr std::string_view kRecordStart = R"({"input":")";

bool IsBlank(std::string_view line) { return line.find_first_not_of(" \t\r") == std::string_view::npos; }

Diagnostic NotARegularFile(const fs::path& path, const fs::file_status& status) {
  if (fs::is_directory(status)) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("{} is a folder: -o names the JSON Lines file", path.string()));
  }
  return Failure(DiagnosticCode::kCannotWriteFile,
                 fmt::format("{} is not a regular file (a device, FIFO or socket): -o names the JSON Lines file",
                             path.string()));
}

Diagnostic Untouched(const fs::path& path, int line, std::string_view what) {
  return Failure(DiagnosticCode::kBatchRecord,
                 fmt::format("{}:{}: {}; {} is not irrmap batch's output, and nothing in it was changed", path.string(),
                             line, what, path.string()),
                 {path.string(), line});
}

// "cannot open PATH (why)", "cannot open PATH for appending (why)".
Diagnostic CannotOpen(std::string_view what, const fs::path& path, int error, std::string_view how = "") {
  return Failure(DiagnosticCode::kCannotWriteFile,
                 fmt::format("{} {}{} ({})", what, path.string(), how, std::strerror(error)));
}

// The record in a --per-file file (at most kMaxRecordBytes), or nullopt.
std::optional<nlohmann::json> ReadRecordFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) > kMaxRecordBytes || ec) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  nlohmann::json record = nlohmann::json::parse(text, nullptr, false);
  if (in.bad() || !RecordKey(record)) return std::nullopt;
  return record;
}

}  // namespace

std::string InputKey(const std::string& input) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(input, ec).lexically_normal();
  if (ec) return input;
  fs::path folder = fs::weakly_canonical(absolute.parent_path(), ec);
  if (ec) folder = absolute.parent_path();
  return (folder / absolute.filename()).string();
}

std::optional<std::string> RecordKey(const nlohmann::json& record) {
  if (!record.is_object() || !record.contains("input") || !record["input"].is_string() ||
      !record.contains("coefficients") || !record["coefficients"].is_array() || !record.contains("constants") ||
      !record["constants"].is_object()) {
    return std::nullopt;
  }
  if (record.contains("path") && record["path"].is_string()) return record["path"].get<std::string>();
  return InputKey(record["input"].get<std::string>());
}

Status BatchOutput::Open(const fs::path& path, bool resume) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) return NotARegularFile(path, status);
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);  // a failure shows in the lock's error
  Result<OutputLock> lock = OutputLock::Take(fs::path(path) += ".lock", path.string());
  if (!lock) return lock.error();
  lock_ = std::move(lock).value();
  path_ = path;
  const int fd = open(path.c_str(), O_RDWR | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0 && errno == ENOENT) return {};  // BeginWriting creates it
  if (fd < 0) return CannotOpen("cannot open", path, errno);
  struct stat opened {};
  Status problem;
  if (fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {  // replaced since the check above
    problem = NotARegularFile(path, fs::status(path, ec));
  } else if (!resume) {
    problem = Failure(DiagnosticCode::kOutputExists,
                      fmt::format("{} exists: pass --resume to continue it, or remove it", path.string()));
  } else {
    problem = ReadRecords(fd, path);
  }
  if (problem.ok()) file_.reset(fdopen(fd, "a"));
  if (problem.ok() && !file_) problem = CannotOpen("cannot open", path, errno, " for appending");
  if (!problem.ok() && !file_) close(fd);
  return problem;
}

Status BatchOutput::BeginWriting() {
  if (file_) return {};
  const int fd = open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return CannotOpen("cannot create", path_, errno);
  file_.reset(fdopen(fd, "a"));
  if (file_) return {};
  const int error = errno;
  close(fd);
  return CannotOpen("cannot open", path_, error, " for appending");
}

Status BatchOutput::ReadRecords(int fd, const fs::path& path) {
  std::array<char, kReadChunkBytes> chunk;
  std::string line;
  int number = 1;
  off_t complete = 0;  // bytes up to the end of the last complete line
  for (;;) {
    const ssize_t got = read(fd, chunk.data(), chunk.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      return Failure(DiagnosticCode::kCannotReadFile,
                     fmt::format("cannot read {} to resume it ({})", path.string(), std::strerror(errno)));
    }
    if (got == 0) break;
    std::string_view rest(chunk.data(), static_cast<std::size_t>(got));
    while (!rest.empty()) {
      const std::size_t newline = rest.find('\n');
      line.append(rest.substr(0, newline));
      if (line.size() > kMaxRecordBytes) {
        return Untouched(path, number, fmt::format("a line longer than any record ({} bytes)", kMaxRecordBytes));
      }
      if (newline == std::string_view::npos) break;
      rest.remove_prefix(newline + 1);
      if (!IsBlank(line)) {
        const nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
        const std::optional<std::string> key = RecordKey(record);
        if (!key) return Untouched(path, number, "not a record (a JSON object with \"input\", \"coefficients\" and \"constants\")");
        if (const Status schema = OtherSchemaVersion(record); !schema.ok()) {
          return Failure(DiagnosticCode::kBatchRecord,
                         fmt::format("{}:{}: {}: one output holds records of one schema, so it is not resumed and "
                                     "nothing in it was changed; write the rest into a new output",
                                     path.string(), number, schema.message()),
                         {path.string(), number});
        }
        completed_.insert(*key);
      }
      complete += static_cast<off_t>(line.size() + 1);
      ++number;
      line.clear();
    }
  }
  if (line.empty()) return {};
  if (!line.starts_with(kRecordStart) && !kRecordStart.starts_with(line)) {
    return Untouched(path, number, "a last line without its newline that is not the start of a record");
  }
  // The start of a record that a stopped run was writing: cut off, so that the next line starts fresh.
  if (ftruncate(fd, complete) != 0) {
    return Failure(DiagnosticCode::kCannotWriteFile,
                   fmt::format("cannot cut the unfinished last line off {} ({})", path.string(), std::strerror(errno)));
  }
  return {};
}

bool BatchOutput::Append(const std::string& line) {
  return std::fwrite(line.data(), 1, line.size(), file_.get()) == line.size() && std::fflush(file_.get()) == 0;
}

std::string PerFileName(std::string input) {
  if (input.starts_with("./")) input.erase(0, 2);
  std::string name;
  for (char c : input) name += c == '/' ? std::string("__") : std::string(1, c);
  return name + ".json";
}

Status CheckPerFileNames(const fs::path& folder, const std::vector<std::string>& inputs,
                         const std::vector<std::string>& todo) {
  std::map<std::string, const std::string*> owners;
  for (const std::string& input : inputs) {
    const auto [owner, fresh] = owners.emplace(PerFileName(input), &input);
    if (!fresh) {
      return Failure(DiagnosticCode::kPerFileCollision,
                     fmt::format("--per-file: {} and {} would both be written to {}; rename one of them or leave out "
                                 "--per-file",
                                 *owner->second, input, (folder / owner->first).string()));
    }
  }
  std::error_code ec;
  for (const std::string& input : todo) {
    const fs::path path = folder / PerFileName(input);
    if (!fs::exists(fs::symlink_status(path, ec))) continue;
    const std::optional<nlohmann::json> record = ReadRecordFile(path);
    if (!record) {
      return Failure(DiagnosticCode::kBatchRecord,
                     fmt::format("--per-file: {} is not a record of irrmap batch; it is left as it is", path.string()));
    }
    if (*RecordKey(*record) != InputKey(input)) {
      return Failure(DiagnosticCode::kPerFileCollision,
                     fmt::format("--per-file: {} holds the record of {}, not of {}; it is left as it is",
                                 path.string(), (*record)["input"].get<std::string>(), input));
    }
  }
  return {};
}

}  // namespace vs11::irradiance
