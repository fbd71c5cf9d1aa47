// `irrmap batch-merge`: the shards' outputs checked against their inputs and joined into one sorted
// file (irradiance/jobs/batch_merge.h); a text report, or JSON with --json.
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "irradiance/cli/subcommands.h"
#include "irradiance/jobs/batch_merge.h"

namespace vs11::irradiance::cli {
namespace {

struct MergeArguments {
  MergeOptions options;
  bool json = false;
};

void PrintReport(const MergeReport& report, const MergeOptions& options) {
  fmt::print("{} inputs, {} records in {} parts: {} missing, {} duplicated, {} not among the inputs\n", report.inputs,
             report.records, report.parts, report.missing.size(), report.duplicated.size(),
             report.unexpected.size());
  if (!report.missing.empty()) fmt::print("missing:\n");
  for (const std::string& input : report.missing) fmt::print("  {}\n", input);
  if (!report.duplicated.empty()) fmt::print("duplicated:\n");
  for (const MergeReport::Duplicate& duplicate : report.duplicated) {
    fmt::print("  {} in {}\n", duplicate.path, fmt::join(duplicate.locations, ", "));
  }
  if (!report.unexpected.empty()) fmt::print("not among the inputs:\n");
  for (const MergeReport::Unexpected& record : report.unexpected) fmt::print("  {} in {}\n", record.path, record.location);
  if (report.written) fmt::print("wrote {} records, sorted by path, to {}\n", report.records, options.output.string());
}

void RunMergeCommand(const MergeArguments& arguments) {
  MergeReport report;
  if (const Status error = MergeBatchOutputs(arguments.options, report); !error.ok()) {
    throw SubcommandFailure(error.message());
  }
  if (arguments.json) {
    fmt::print("{}\n", MergeReportJson(report, arguments.options.output).dump(2));
  } else {
    PrintReport(report, arguments.options);
  }
  if (!report.complete()) {
    throw SubcommandFailure(fmt::format("the parts do not hold every input exactly once{}",
                                        arguments.options.output.empty()
                                            ? ""
                                            : fmt::format("; {} was not written", arguments.options.output.string())));
  }
}

}  // namespace

void AddBatchMergeCommand(CLI::App& app) {
  auto arguments = std::make_shared<MergeArguments>();
  CLI::App* merge = app.add_subcommand(
      "batch-merge",
      "Checks that the outputs of irrmap batch's shards (or vs11.dask's parts) hold every input exactly\n"
      "once, and joins them into one JSON Lines file sorted by path.");
  merge->footer(
      "INPUT and --list are the shards' own inputs (the same paths, patterns and list files), expanded\n"
      "as irrmap batch expands them; a record matches an input by its \"path\" (the input's canonical\n"
      "path), so run it where the inputs have the paths the shards saw. Inputs with no record, inputs\n"
      "with more than one (each PART:LINE) and records of no input are listed; then the exit status is\n"
      "1 and -o FILE is not written. Otherwise -o FILE gets every record's line as its shard wrote it,\n"
      "sorted by path, written to a temporary and renamed into place (no -o: only the check).\n"
      "--json prints the report as JSON on stdout: inputs, parts, records, missing, duplicated\n"
      "([{\"path\", \"in\": [PART:LINE...]}]), unexpected, complete, output (null if not written).\n"
      "Exit status: 0 every input once (and -o FILE written), 1 an input missing or duplicated, a\n"
      "record of no input, a part line that is not a record, or -o FILE cannot be written; 2 a usage error.\n"
      "\n"
      "Examples:\n"
      "  irrmap batch-merge --list all.txt --parts 'out/part-*.jsonl' -o sh.jsonl\n"
      "  irrmap batch-merge --list all.txt --parts 'out/part-*.jsonl' --json\n");
  merge->add_option("INPUT", arguments->options.inputs, "the shards' environment files or glob patterns (quote them)");
  merge->add_option("--list", arguments->options.list_files, "the shards' list files of inputs; may repeat")
      ->check(CLI::ExistingFile);
  merge->add_option("--parts", arguments->options.parts, "the shards' JSON Lines outputs: files or glob patterns")
      ->required();
  merge->add_option("-o,--output", arguments->options.output, "the merged JSON Lines file (default: only check)");
  merge->add_flag("--json", arguments->json, "print the report as JSON on stdout");
  merge->callback([arguments] {
    if (arguments->options.inputs.empty() && arguments->options.list_files.empty()) {
      throw CLI::ValidationError("INPUT", "no inputs given: the shards' inputs (INPUT... or --list FILE)");
    }
    RunMergeCommand(*arguments);
  });
}

}  // namespace vs11::irradiance::cli
