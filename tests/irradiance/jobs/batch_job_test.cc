// irrmap batch (irradiance/jobs/batch_job.h): records of good files, bad files reported and skipped,
// resuming a cut-off output, and shards that partition the inputs exactly.
#include "irradiance/jobs/batch_job.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/level_choice.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/run_tool.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
constexpr int kFace = 16;

class BatchJob : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("vs11_batch_{}_{}", getpid(), ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path Path(const std::string& name) const { return dir_ / name; }

  // A sky cross written as EXR; the sun's azimuth makes every file different.
  std::string WriteSky(const std::string& name, double azimuth) {
    SkyParams params;
    params.sun_azimuth_degrees = azimuth;
    EXPECT_EQ(WriteCrossExr(MakeSky(kFace, params), Path(name)), std::nullopt);
    return Path(name).string();
  }

  void WriteBytes(const std::string& name, const std::string& bytes) {
    std::ofstream(Path(name), std::ios::binary) << bytes;
  }

  static std::string ReadText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // Records of a JSON Lines file by input.
  static std::map<std::string, nlohmann::json> Records(const fs::path& path) {
    std::map<std::string, nlohmann::json> records;
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      nlohmann::json record = nlohmann::json::parse(line);
      const std::string input = record["input"];
      EXPECT_EQ(records.count(input), 0u) << input << " twice";
      records[input] = std::move(record);
    }
    return records;
  }

  BatchOptions Options(std::vector<std::string> inputs) const {
    BatchOptions options;
    options.inputs = std::move(inputs);
    options.output = Path("out.jsonl");
    options.threads = 2;
    return options;
  }

  fs::path dir_;
};

TEST_F(BatchJob, AGoodFileGetsItsCoefficientsConstantsLevelAndError) {
  const std::string sky = WriteSky("sky.exr", 30.0);
  BatchOptions options = Options({sky});
  options.per_file_dir = Path("each");
  BatchSummary summary;
  ASSERT_EQ(RunBatch(options, summary), std::nullopt);
  EXPECT_EQ(summary.succeeded, 1u);
  EXPECT_TRUE(summary.failures.empty());

  const std::map<std::string, nlohmann::json> records = Records(options.output);
  ASSERT_EQ(records.count(sky), 1u);
  const nlohmann::json& record = records.at(sky);
  EXPECT_EQ(record["face_size"], kFace);
  EXPECT_EQ(record["layout"], "hcross");
  // The same level choice and coefficients as computing them here.
  LoadResult loaded = LoadEnvironment(sky);
  ASSERT_TRUE(loaded.ok());
  std::optional<CubeMipChain> mips = BuildEnvironmentMips(loaded.environment->cube);
  std::optional<BasisPyramid> basis = BuildBasisPyramid(kFace);
  std::vector<Sh9Rgb> levels;
  for (int level = 0; level < LevelCount(kFace); ++level) levels.push_back(ProjectLevel(*mips, *basis, level));
  const std::vector<double> estimated = EstimateLevelErrors(levels, SphereNormals(kLevelErrorNormals), kDefaultErrorMetric);
  const int level = CoarsestLevelWithin(estimated, kDefaultMaxLevelError);
  EXPECT_EQ(record["level"], level);
  EXPECT_EQ(record["level_size"], kFace >> level);
  EXPECT_DOUBLE_EQ(record["estimated_error"].get<double>(), estimated[level]);
  ASSERT_EQ(record["coefficients"].size(), 9u);
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(record["coefficients"][i][c].get<double>(), levels[level].coefficients[i][c]);
  }
  EXPECT_EQ(record["constants"].size(), 7u);
  // The per-file output holds the same record.
  std::string name;
  for (char c : sky) name += c == '/' ? std::string("__") : std::string(1, c);
  EXPECT_EQ(nlohmann::json::parse(ReadText(Path("each") / (name + ".json"))), record);
}

TEST_F(BatchJob, BadFilesAreReportedWithTheirReasonAndSkipped) {
  const std::string good = WriteSky("good.exr", 0.0);
  const std::string bytes = ReadText(good);
  WriteBytes("truncated.exr", bytes.substr(0, bytes.size() / 2));
  WriteBytes("corrupt.exr", std::string(4096, '\x5a'));
  WriteBytes("unsupported.txt", "not an image\n");
  BatchOptions options = Options({Path("*.exr").string(), Path("unsupported.txt").string(), Path("missing.exr").string()});
  std::vector<std::string> reported;
  BatchSummary summary;
  ASSERT_EQ(RunBatch(options, summary, {}, [&](const BatchFailure& failure) { reported.push_back(failure.input); }),
            std::nullopt);
  EXPECT_EQ(summary.selected, 5u);
  EXPECT_EQ(summary.succeeded, 1u);
  ASSERT_EQ(summary.failures.size(), 4u);
  EXPECT_EQ(reported.size(), 4u);
  std::set<std::string> failed;
  for (const BatchFailure& failure : summary.failures) {
    failed.insert(fs::path(failure.input).filename().string());
    EXPECT_FALSE(failure.reason.empty()) << failure.input;
  }
  EXPECT_EQ(failed, (std::set<std::string>{"corrupt.exr", "missing.exr", "truncated.exr", "unsupported.txt"}));
  const std::map<std::string, nlohmann::json> records = Records(options.output);
  EXPECT_EQ(records.size(), 1u);
  EXPECT_EQ(records.count(good), 1u);
}

TEST_F(BatchJob, ResumeDropsACutOffLineAndSkipsFinishedInputs) {
  std::vector<std::string> inputs;
  for (int i = 0; i < 4; ++i) inputs.push_back(WriteSky(fmt::format("sky{}.exr", i), 40.0 * i));
  BatchOptions options = Options({Path("sky*.exr").string()});
  BatchSummary summary;
  ASSERT_EQ(RunBatch(options, summary), std::nullopt);
  const std::map<std::string, nlohmann::json> complete = Records(options.output);
  ASSERT_EQ(complete.size(), 4u);

  // An interrupted run: two finished lines and half of a third.
  const std::string text = ReadText(options.output);
  std::size_t second_end = text.find('\n', text.find('\n') + 1) + 1;
  std::ofstream(options.output, std::ios::binary | std::ios::trunc) << text.substr(0, second_end + 40);

  EXPECT_NE(RunBatch(options, summary), std::nullopt) << "an existing output needs --resume";
  options.resume = true;
  ASSERT_EQ(RunBatch(options, summary), std::nullopt);
  EXPECT_EQ(summary.resumed, 2u);
  EXPECT_EQ(summary.succeeded, 2u);
  EXPECT_EQ(Records(options.output), complete);  // each input once, the same records

  ASSERT_EQ(RunBatch(options, summary), std::nullopt);  // nothing left to do
  EXPECT_EQ(summary.resumed, 4u);
  EXPECT_EQ(summary.succeeded, 0u);
}

TEST_F(BatchJob, ShardsPartitionTheInputsExactly) {
  std::vector<std::string> inputs;
  for (int i = 0; i < 23; ++i) inputs.push_back(fmt::format("env{}.exr", i));
  for (int count : {1, 2, 3, 7, 23, 40}) {
    std::multiset<std::string> seen;
    for (int k = 0; k < count; ++k) {
      const std::vector<std::string> shard = ShardOf(inputs, k, count);
      EXPECT_LE(shard.size(), inputs.size() / count + 1);
      seen.insert(shard.begin(), shard.end());
    }
    EXPECT_EQ(seen, std::multiset<std::string>(inputs.begin(), inputs.end())) << count << " shards";
  }
  // End to end: three shards of five files write every file exactly once between them.
  for (int i = 0; i < 5; ++i) WriteSky(fmt::format("s{}.exr", i), 70.0 * i);
  std::map<std::string, nlohmann::json> all;
  for (int k = 0; k < 3; ++k) {
    BatchOptions options = Options({Path("s*.exr").string()});
    options.output = Path(fmt::format("part{}.jsonl", k));
    options.shard_index = k;
    options.shard_count = 3;
    BatchSummary summary;
    ASSERT_EQ(RunBatch(options, summary), std::nullopt);
    for (auto& [input, record] : Records(options.output)) EXPECT_TRUE(all.emplace(input, record).second) << input;
  }
  EXPECT_EQ(all.size(), 5u);
}

TEST_F(BatchJob, InputsComeFromListsAndPatternsSortedOnce) {
  WriteSky("b.exr", 0.0);
  WriteSky("a.exr", 10.0);
  std::ofstream(Path("list.txt")) << "# comment\n\n" << Path("b.exr").string() << "\n  " << Path("*.exr").string() << "\n";
  std::string error;
  const std::vector<std::string> inputs = ExpandBatchInputs({Path("a.exr").string()}, {Path("list.txt")}, error);
  EXPECT_EQ(error, "");
  EXPECT_EQ(inputs, (std::vector<std::string>{Path("a.exr").string(), Path("b.exr").string()}));
  ExpandBatchInputs({Path("*.none").string()}, {}, error);
  EXPECT_NE(error.find("matches no file"), std::string::npos) << error;
  error.clear();
  ExpandBatchInputs({}, {Path("no-list.txt")}, error);
  EXPECT_NE(error.find("no-list.txt"), std::string::npos) << error;
}

TEST(BatchShard, ParsesKOverN) {
  EXPECT_EQ(ParseShard("0/1"), (std::pair{0, 1}));
  EXPECT_EQ(ParseShard("3/16"), (std::pair{3, 16}));
  for (const char* bad : {"", "1", "1/1", "-1/4", "4/4", "a/b", "1/2x", "1:2"}) EXPECT_EQ(ParseShard(bad), std::nullopt) << bad;
}

TEST_F(BatchJob, CommandExitsOneAndListsTheFailuresAfterWritingTheRest) {
  const std::string good = WriteSky("good.exr", 0.0);
  WriteBytes("bad.exr", "garbage");
  const testing::CommandResult run = testing::RunIrrmap("batch " + Path("*.exr").string() + " -o " +
                                                        Path("out.jsonl").string());
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("skipped " + Path("bad.exr").string()), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("1 of 2 inputs failed"), std::string::npos) << run.output;
  EXPECT_EQ(Records(Path("out.jsonl")).count(good), 1u);
  const testing::CommandResult usage = testing::RunIrrmap("batch " + good + " -o " + Path("x.jsonl").string() + " --shard 2/2");
  EXPECT_EQ(usage.status, 2) << usage.output;
}

}  // namespace
}  // namespace vs11::irradiance
