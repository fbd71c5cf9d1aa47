// irrmap batch-merge (irradiance/jobs/batch_merge.h): shards joined into one sorted file when every
// input is there exactly once; what is missing, duplicated or of no input reported (and nothing
// written); lines that are not records named by part:line; the tool's text, --json and exit status.
#include "irradiance/jobs/batch_merge.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/batch_output.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;

class BatchMerge : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("vs11_merge_{}_{}", getpid(), ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "data");
    for (int i = 0; i < 6; ++i) {
      inputs_.push_back((dir_ / "data" / fmt::format("env{}.pfm", i)).string());
      std::ofstream(inputs_.back()) << "PF\n";  // never read: the records are written by hand
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A record as irrmap batch writes it (no numbers needed here), with an extra field of a later version.
  static std::string Record(const std::string& input) {
    nlohmann::ordered_json record = {{"input", input},
                                     {"path", InputKey(input)},
                                     {"coefficients", nlohmann::json::array()},
                                     {"constants", nlohmann::json::object()},
                                     {"schema", 2}};
    return record.dump();
  }

  std::string WritePart(const std::string& name, const std::vector<std::string>& inputs) {
    std::ofstream out(dir_ / name);
    for (const std::string& input : inputs) out << Record(input) << "\n";
    return (dir_ / name).string();
  }

  MergeOptions Options() const {
    MergeOptions options;
    options.inputs = {(dir_ / "data" / "*.pfm").string()};
    options.parts = {(dir_ / "part-*.jsonl").string()};
    options.output = dir_ / "merged.jsonl";
    return options;
  }

  static std::string ReadText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
  std::vector<std::string> inputs_;  // sorted
};

TEST_F(BatchMerge, EveryInputOnceIsJoinedSortedByPathWithEachLineAsItWas) {
  WritePart("part-1.jsonl", {inputs_[5], inputs_[1], inputs_[3]});
  WritePart("part-0.jsonl", {inputs_[4], inputs_[0], inputs_[2]});
  MergeReport report;
  ASSERT_EQ(MergeBatchOutputs(Options(), report).message(), "");
  EXPECT_TRUE(report.complete());
  EXPECT_TRUE(report.written);
  EXPECT_EQ(report.inputs, 6u);
  EXPECT_EQ(report.parts, 2u);
  EXPECT_EQ(report.records, 6u);
  std::string expected;
  for (const std::string& input : inputs_) expected += Record(input) + "\n";  // extra fields kept
  EXPECT_EQ(ReadText(dir_ / "merged.jsonl"), expected);
  // Running it again: the merged file is no part (its name does not match), and is replaced whole.
  ASSERT_EQ(MergeBatchOutputs(Options(), report).message(), "");
  EXPECT_EQ(ReadText(dir_ / "merged.jsonl"), expected);
}

TEST_F(BatchMerge, MissingDuplicatedAndForeignRecordsAreListedAndNothingIsWritten) {
  const std::string other = (dir_ / "elsewhere.pfm").string();
  WritePart("part-0.jsonl", {inputs_[0], inputs_[2], inputs_[4]});
  WritePart("part-1.jsonl", {inputs_[1], inputs_[2], other});  // inputs_[3] and [5] missing
  MergeReport report;
  ASSERT_EQ(MergeBatchOutputs(Options(), report).message(), "");
  EXPECT_FALSE(report.complete());
  EXPECT_FALSE(report.written);
  EXPECT_FALSE(fs::exists(dir_ / "merged.jsonl"));
  EXPECT_EQ(report.missing, (std::vector<std::string>{inputs_[3], inputs_[5]}));
  ASSERT_EQ(report.duplicated.size(), 1u);
  EXPECT_EQ(report.duplicated[0].path, InputKey(inputs_[2]));
  EXPECT_EQ(report.duplicated[0].locations,
            (std::vector<std::string>{(dir_ / "part-0.jsonl").string() + ":2", (dir_ / "part-1.jsonl").string() + ":2"}));
  ASSERT_EQ(report.unexpected.size(), 1u);
  EXPECT_EQ(report.unexpected[0].location, (dir_ / "part-1.jsonl").string() + ":3");

  const nlohmann::json json = MergeReportJson(report, dir_ / "merged.jsonl");
  EXPECT_EQ(json["missing"].size(), 2u);
  EXPECT_EQ(json["duplicated"][0]["in"].size(), 2u);
  EXPECT_EQ(json["complete"], false);
  EXPECT_TRUE(json["output"].is_null());
}

TEST_F(BatchMerge, ALineThatIsNoRecordIsNamedByPartAndLine) {
  const std::string part = WritePart("part-0.jsonl", {inputs_[0], inputs_[1]});
  std::ofstream(part, std::ios::app) << "{\"input\": \"x\"}\n";
  MergeReport report;
  Status error = MergeBatchOutputs(Options(), report);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.message(), part + ":3: not a record of irrmap batch");

  WritePart("part-0.jsonl", {inputs_[0]});
  std::ofstream(part, std::ios::app) << Record(inputs_[1]).substr(0, 30);  // a shard stopped mid-line
  error = MergeBatchOutputs(Options(), report);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find(part + ":2: not a record of irrmap batch (cut off"), std::string::npos)
      << error.message();
  EXPECT_FALSE(fs::exists(dir_ / "merged.jsonl"));
}

TEST_F(BatchMerge, AnOutputThatIsAPartOrAnInputIsRefused) {
  const std::string part = WritePart("part-0.jsonl", inputs_);
  MergeOptions options = Options();
  options.output = part;
  MergeReport report;
  Status error = MergeBatchOutputs(options, report);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find("refusing to overwrite"), std::string::npos) << error.message();
  options.output = inputs_[0];
  EXPECT_FALSE(MergeBatchOutputs(options, report).ok());
  options.parts = {(dir_ / "nothing-*.jsonl").string()};
  options.output = dir_ / "merged.jsonl";
  error = MergeBatchOutputs(options, report);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find("matches no file"), std::string::npos) << error.message();
}

// End to end: irrmap batch in three shards, one of them run twice (a requeued job without
// --resume into another file), then irrmap batch-merge.
TEST_F(BatchMerge, TheToolMergesRealShardsAndExitsOneOnADuplicate) {
  fs::create_directories(dir_ / "skies");
  for (int i = 0; i < 5; ++i) {
    SkyParams params;
    params.sun_azimuth_degrees = 40.0 * i;
    ASSERT_EQ(WriteCrossExr(MakeSky(8, params), dir_ / "skies" / fmt::format("sky{}.exr", i)).message(), "");
  }
  const std::string inputs = fmt::format("'{}/skies/*.exr'", dir_.string());
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(vs11::testing::RunTool("irradiance/irrmap", fmt::format("batch {} -o {}/out/part-{}.jsonl --shard {}/3",
                                                                      inputs, dir_.string(), k, k)).status, 0);
  }
  const std::string merge = fmt::format("batch-merge {} --parts '{}/out/part-*.jsonl' -o {}/sh.jsonl", inputs,
                                        dir_.string(), dir_.string());
  vs11::testing::CommandResult result = vs11::testing::RunTool("irradiance/irrmap", merge);
  ASSERT_EQ(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("5 inputs, 5 records in 3 parts: 0 missing, 0 duplicated"), std::string::npos)
      << result.output;
  std::vector<std::string> keys;
  std::ifstream merged(dir_ / "sh.jsonl");
  for (std::string line; std::getline(merged, line);) keys.push_back(nlohmann::json::parse(line)["path"]);
  EXPECT_EQ(keys.size(), 5u);
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));

  fs::copy_file(dir_ / "out" / "part-1.jsonl", dir_ / "out" / "part-1-again.jsonl");
  fs::remove(dir_ / "sh.jsonl");
  result = vs11::testing::RunTool("irradiance/irrmap", merge);
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find("duplicated:\n  " + (dir_ / "skies" / "sky1.exr").string() + " in "), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("irrmap: error: the parts do not hold every input exactly once; "), std::string::npos)
      << result.output;
  EXPECT_FALSE(fs::exists(dir_ / "sh.jsonl"));

  result = vs11::testing::RunCommandLine(std::string(VS11_BINARY_DIR) + "/irradiance/irrmap " + merge + " --json");
  EXPECT_EQ(result.status, 1);
  const nlohmann::json json = nlohmann::json::parse(result.output);
  EXPECT_EQ(json["duplicated"].size(), 2u);  // part-1 holds sky1 and sky4
  EXPECT_EQ(json["records"], 7);

  EXPECT_EQ(vs11::testing::RunTool("irradiance/irrmap", "batch-merge " + inputs).status, 2) << "--parts is required";
}

}  // namespace
}  // namespace vs11::irradiance
