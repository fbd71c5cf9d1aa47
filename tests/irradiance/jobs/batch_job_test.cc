// irrmap batch (irradiance/jobs/batch_job.h): records of good files, bad files reported and skipped,
// resuming a cut-off output (and changing nothing in a file that is not one), the output's lock,
// inputs known by their canonical path, --per-file names that collide, and shards that partition the
// inputs exactly.
#include "irradiance/jobs/batch_job.h"

#include <fcntl.h>
#include <sys/file.h>
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
    EXPECT_EQ(WriteCrossExr(MakeSky(kFace, params), Path(name)).message(), "");
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
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.succeeded, 1u);
  EXPECT_TRUE(summary.failures.empty());

  const std::map<std::string, nlohmann::json> records = Records(options.output);
  ASSERT_EQ(records.count(sky), 1u);
  const nlohmann::json& record = records.at(sky);
  EXPECT_EQ(record["face_size"], kFace);
  EXPECT_EQ(record["layout"], "hcross");
  // The same level choice and coefficients as computing them here.
  Result<LoadedEnvironment> loaded = LoadEnvironment(sky);
  ASSERT_TRUE(loaded.ok());
  std::optional<CubeMipChain> mips = BuildEnvironmentMips(loaded->cube);
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
  ASSERT_EQ(
      RunBatch(options, summary, {}, [&](const BatchFailure& failure) { reported.push_back(failure.input); }).message(),
      "");
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
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  const std::map<std::string, nlohmann::json> complete = Records(options.output);
  ASSERT_EQ(complete.size(), 4u);

  // An interrupted run: two finished lines and half of a third.
  const std::string text = ReadText(options.output);
  std::size_t second_end = text.find('\n', text.find('\n') + 1) + 1;
  std::ofstream(options.output, std::ios::binary | std::ios::trunc) << text.substr(0, second_end + 40);

  const Status exists = RunBatch(options, summary);
  ASSERT_FALSE(exists.ok()) << "an existing output needs --resume";
  EXPECT_EQ(exists.error().code, DiagnosticCode::kOutputExists) << exists.message();
  options.resume = true;
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.resumed, 2u);
  EXPECT_EQ(summary.succeeded, 2u);
  EXPECT_EQ(Records(options.output), complete);  // each input once, the same records

  ASSERT_EQ(RunBatch(options, summary).message(), "");  // nothing left to do
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
    ASSERT_EQ(RunBatch(options, summary).message(), "");
    for (auto& [input, record] : Records(options.output)) EXPECT_TRUE(all.emplace(input, record).second) << input;
  }
  EXPECT_EQ(all.size(), 5u);
}

TEST_F(BatchJob, InputsComeFromListsAndPatternsSortedOnce) {
  WriteSky("b.exr", 0.0);
  WriteSky("a.exr", 10.0);
  std::ofstream(Path("list.txt")) << "# comment\n\n" << Path("b.exr").string() << "\n  " << Path("*.exr").string() << "\n";
  const Result<std::vector<std::string>> inputs = ExpandBatchInputs({Path("a.exr").string()}, {Path("list.txt")});
  ASSERT_TRUE(inputs) << inputs.message();
  EXPECT_EQ(*inputs, (std::vector<std::string>{Path("a.exr").string(), Path("b.exr").string()}));
  const Result<std::vector<std::string>> none = ExpandBatchInputs({Path("*.none").string()}, {});
  EXPECT_EQ(none.error().code, DiagnosticCode::kNoSuchInput);
  EXPECT_NE(none.message().find("matches no file"), std::string::npos) << none.message();
  const Result<std::vector<std::string>> no_list = ExpandBatchInputs({}, {Path("no-list.txt")});
  EXPECT_EQ(no_list.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_NE(no_list.message().find("no-list.txt"), std::string::npos) << no_list.message();
  // A list's entry that matches nothing is placed at the list's line.
  std::ofstream(Path("bad-list.txt")) << "# comment\n" << Path("*.none").string() << "\n";
  const Result<std::vector<std::string>> bad_entry = ExpandBatchInputs({}, {Path("bad-list.txt")});
  ASSERT_FALSE(bad_entry.ok());
  EXPECT_EQ(bad_entry.error().loc, (SourceLoc{Path("bad-list.txt").string(), 2, 0}));
  EXPECT_TRUE(bad_entry.message().starts_with(Path("bad-list.txt").string() + ":2: ")) << bad_entry.message();
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

// --resume reads the whole file before it changes anything: a file that is not wholly irrmap batch's
// output (an input given as -o by mistake, notes, another tool's JSON Lines, a record followed by
// something else) is left byte for byte as it was, and the error names the first line that is wrong.
TEST_F(BatchJob, ResumeChangesNothingInAFileThatIsNotItsOutput) {
  const std::string good = WriteSky("good.exr", 0.0);
  BatchSummary summary;
  BatchOptions first = Options({good});
  ASSERT_EQ(RunBatch(first, summary).message(), "");
  const std::string record = ReadText(first.output);
  ASSERT_TRUE(record.ends_with("\n"));

  std::string pfm = "PF\n4 2\n-1.0\n";
  for (int i = 0; i < 4 * 2 * 3; ++i) pfm += std::string("\x00\x00\x80\x3f", 4);  // 1.0f, no newline at the end
  const std::vector<std::pair<std::string, std::string>> files = {
      {"in.pfm", pfm},
      {"notes.txt", "line 1\ntail"},
      {"other.jsonl", "{\"input\": \"a.exr\", \"score\": 3}\n"},
      {"record_then_text.jsonl", record + "not json\n" + record},
      {"record_then_tail.jsonl", record + "tail"},
  };
  const std::map<std::string, std::string> expected_line = {{"in.pfm", ":1: "},
                                                            {"notes.txt", ":1: "},
                                                            {"other.jsonl", ":1: "},
                                                            {"record_then_text.jsonl", ":2: "},
                                                            {"record_then_tail.jsonl", ":2: "}};
  for (const auto& [name, bytes] : files) {
    WriteBytes(name, bytes);
    BatchOptions options = Options({good});
    options.output = Path(name);
    options.resume = true;
    const Status error = RunBatch(options, summary);
    ASSERT_FALSE(error.ok()) << name;
    EXPECT_EQ(error.error().code, DiagnosticCode::kBatchRecord) << name;
    EXPECT_NE(error.message().find(Path(name).string() + expected_line.at(name)), std::string::npos)
        << error.message();
    EXPECT_NE(error.message().find("nothing in it was changed"), std::string::npos) << error.message();
    EXPECT_EQ(ReadText(Path(name)), bytes) << name;
    EXPECT_FALSE(fs::exists(Path(name + ".lock"))) << name;
  }
  // The start of a record without its newline is a stopped run's: cut off, and the input done again.
  WriteBytes("cut.jsonl", record + "{\"inp");
  BatchOptions options = Options({good, WriteSky("other.exr", 90.0)});
  options.output = Path("cut.jsonl");
  options.resume = true;
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.resumed, 1u);
  EXPECT_EQ(summary.succeeded, 1u);
  EXPECT_EQ(Records(options.output).size(), 2u);
}

// The lock on the output: held by another process (here, by this one through another descriptor), the
// run ends before any work with the holder's words; a lock file left by a process that has ended
// (no flock on it) blocks nothing, and is gone after the run.
TEST_F(BatchJob, AHeldOutputLockRefusesTheRunAndAStaleOneDoesNot) {
  const std::string good = WriteSky("good.exr", 0.0);
  BatchOptions options = Options({good});
  options.resume = true;
  const fs::path lock_file = Path("out.jsonl.lock");
  const std::string holder = "pid 4242 on node17 since 2024-01-02 03:04:05 +0000\n";
  WriteBytes("out.jsonl.lock", holder);
  const int fd = open(lock_file.c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  BatchSummary summary;
  const Status error = RunBatch(options, summary);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find(options.output.string() + " is in use by another irrmap batch: pid 4242 on node17 since "
                        "2024-01-02 03:04:05 +0000"),
            std::string::npos)
      << error.message();
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_EQ(ReadText(lock_file), holder);
  close(fd);  // the holder ends; its lock file stays behind

  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.succeeded, 1u);
  EXPECT_FALSE(fs::exists(lock_file));
}

// A --per-file folder is locked per shard: another run of the same shard into it is refused, another
// shard may write beside it (their inputs, and so their names, differ).
TEST_F(BatchJob, APerFileFolderIsLockedForItsShard) {
  const std::string good = WriteSky("good.exr", 0.0);
  fs::create_directories(Path("each"));
  const fs::path lock_file = Path("each") / ".irrmap-batch-shard-0-of-1.lock";
  WriteBytes("each/.irrmap-batch-shard-0-of-1.lock", "pid 4242 on node17 since 2024-01-02 03:04:05 +0000\n");
  const int fd = open(lock_file.c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(flock(fd, LOCK_EX | LOCK_NB), 0);
  BatchOptions options = Options({good});
  options.per_file_dir = Path("each");
  BatchSummary summary;
  const Status error = RunBatch(options, summary);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find("is in use by another irrmap batch: pid 4242 on node17"), std::string::npos)
      << error.message();
  EXPECT_EQ(Records(options.output).size(), 0u);

  options.shard_count = 2;
  options.output = Path("shard0of2.jsonl");
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.succeeded, 1u);
  close(fd);
}

// x/y.exr and x__y.exr would both be written to x__y.exr.json: refused before any work, as is a file
// of that name that holds another input's record (written by an earlier run).
TEST_F(BatchJob, PerFileNamesThatCollideAreRefusedBeforeAnyWork) {
  fs::create_directories(Path("x"));
  const std::string nested = WriteSky("x/y.exr", 0.0);
  const std::string flat = WriteSky("x__y.exr", 60.0);
  BatchOptions options = Options({nested, flat});
  options.per_file_dir = Path("each");
  BatchSummary summary;
  const Status error = RunBatch(options, summary);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kPerFileCollision);
  EXPECT_NE(error.message().find(nested + " and " + flat + " would both be written to "), std::string::npos)
      << error.message();
  EXPECT_FALSE(fs::exists(options.output));
  EXPECT_FALSE(fs::exists(Path("each")) && !fs::is_empty(Path("each")));

  options.inputs = {nested};
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  options.inputs = {flat};
  options.output = Path("flat.jsonl");
  const Status overwrite = RunBatch(options, summary);
  ASSERT_FALSE(overwrite.ok());
  EXPECT_EQ(overwrite.error().code, DiagnosticCode::kPerFileCollision);
  EXPECT_NE(overwrite.message().find("holds the record of " + nested + ", not of " + flat), std::string::npos)
      << overwrite.message();
  EXPECT_FALSE(fs::exists(options.output));
}

// An input is known by its canonical path: a run with relative paths, resumed with absolute ones (or
// with "." and ".." in them), does no input again; the same file named twice is one input.
TEST_F(BatchJob, ResumeKnowsAnInputByItsCanonicalPath) {
  const std::string a = WriteSky("a.exr", 0.0);
  const std::string b = WriteSky("b.exr", 45.0);
  const std::string relative_a = fs::relative(a).string();
  BatchOptions options = Options({relative_a, fs::relative(b).string()});
  ASSERT_NE(relative_a, a);
  BatchSummary summary;
  ASSERT_EQ(RunBatch(options, summary).message(), "");
  EXPECT_EQ(summary.succeeded, 2u);

  options.resume = true;
  for (const std::vector<std::string>& inputs :
       {std::vector<std::string>{a, b}, std::vector<std::string>{(Path(".") / "a.exr").string(),
                                                                 (Path("..") / dir_.filename() / "b.exr").string()}}) {
    options.inputs = inputs;
    ASSERT_EQ(RunBatch(options, summary).message(), "");
    EXPECT_EQ(summary.resumed, 2u) << inputs[0];
    EXPECT_EQ(summary.succeeded, 0u) << inputs[0];
  }
  EXPECT_EQ(Records(options.output).size(), 2u);

  EXPECT_EQ(ExpandBatchInputs({a, relative_a, (Path(".") / "a.exr").string()}, {}).value().size(), 1u);
}

}  // namespace
}  // namespace vs11::irradiance
