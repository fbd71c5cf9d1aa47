// libFuzzer target: arbitrary bytes as a shard's output through irradiance::MergeBatchOutputs (irrmap
// batch-merge's reader of part files). The bytes go to a temporary part file, since the merge takes
// paths; the inputs are two paths that need not exist (a record of either one, once, merges). A
// merge that reports success wrote its output, and the output is the records again.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "irradiance/jobs/batch_merge.h"

namespace {

const std::filesystem::path& ScratchFolder() {
  static const std::filesystem::path path = [] {
    std::filesystem::path folder =
        std::filesystem::temp_directory_path() / ("vs11_fuzz_batch_merge_" + std::to_string(getpid()));
    std::filesystem::create_directories(folder);
    return folder;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path part = ScratchFolder() / "part-0.jsonl";
  {
    std::ofstream out(part, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  vs11::irradiance::MergeOptions options;
  options.inputs = {"/fuzz/a.exr", "/fuzz/b.exr"};
  options.parts = {part.string()};
  options.output = ScratchFolder() / "merged.jsonl";
  vs11::irradiance::MergeReport report;
  const vs11::Status error = vs11::irradiance::MergeBatchOutputs(options, report);
  if (error.ok() && report.complete()) {
    vs11::irradiance::MergeReport again;
    options.parts = {options.output.string()};
    options.output = ScratchFolder() / "merged-again.jsonl";
    if (!vs11::irradiance::MergeBatchOutputs(options, again).ok() || !again.complete() || again.records != 2) {
      __builtin_trap();
    }
  }
  (void)vs11::irradiance::MergeReportJson(report, options.output).dump();
  return 0;
}
