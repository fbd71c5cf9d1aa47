// irrmap batch under concurrency and interruption: every record at --threads 1, 2, 4 and 8 is what a
// single-file irrmap run gives for that file (BC6H and 8-bit DDS cube maps of two sizes, copies of
// the same file among them, EXR crosses, HDR and PFM lat-longs), a run killed with SIGKILL again
// and again, resumed each time, ends with every input once and the values of an uninterrupted run,
// and two --resume runs started at once into one output write every input once between them.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "irradiance/io/environment_io.h"
#include "irradiance/io/environments.h"
#include "irradiance/jobs/batch_job.h"
#include "irradiance/jobs/irrmap_job.h"
#include "tests/irradiance/io/dds_test_files.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using envtest::TempFolderTest;

// Coefficients agree to this fraction of the largest one (both runs sum the same texels in the same
// order, so they are expected to be equal; the bound allows for a different summation order).
constexpr double kCoefficientTolerance = 1e-6;
constexpr int kLatLongFaceSize = 64;  // --face-size for the lat-long inputs, in both runs

std::map<std::string, nlohmann::json> Records(const fs::path& path) {
  std::map<std::string, nlohmann::json> records;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    nlohmann::json record = nlohmann::json::parse(line, nullptr, false);
    EXPECT_FALSE(record.is_discarded()) << "not JSON: " << line;
    if (record.is_discarded()) continue;
    const std::string input = record["input"];
    EXPECT_EQ(records.count(input), 0u) << input << " twice in " << path;
    records[input] = std::move(record);
  }
  return records;
}

double LargestMagnitude(const nlohmann::json& coefficients) {
  double largest = 0.0;
  for (const nlohmann::json& rgb : coefficients) {
    for (const nlohmann::json& value : rgb) largest = std::max(largest, std::abs(value.get<double>()));
  }
  return largest;
}

// The largest difference between two records' coefficients, as a fraction of the largest of
// `expected`'s.
double CoefficientDifference(const nlohmann::json& actual, const nlohmann::json& expected) {
  if (actual.size() != 9 || expected.size() != 9) return std::numeric_limits<double>::infinity();
  double difference = 0.0;
  for (int i = 0; i < 9; ++i) {
    for (int c = 0; c < 3; ++c) {
      difference = std::max(difference, std::abs(actual[i][c].get<double>() - expected[i][c].get<double>()));
    }
  }
  return difference / LargestMagnitude(expected);
}

class BatchConcurrency : public TempFolderTest {
 protected:
  // Several face sizes and formats, in the folder in/; the DDS cube maps come in copies.
  std::vector<std::string> WriteInputs() {
    fs::create_directories(Path("in"));
    std::vector<std::string> inputs;
    const auto add = [&](const std::string& name) {
      inputs.push_back(Input(name));
      return fs::path(inputs.back());
    };
    for (int size : {64, 128}) {
      const std::string sky = envtest::SkyBc6hCube(size, glm::dvec3(0.3, 0.8, 0.5));
      for (int copy = 0; copy < 4; ++copy) envtest::WriteBytes(add(fmt::format("bc6h{}_{}.dds", size, copy)), sky);
      envtest::WriteBytes(add(fmt::format("bc6h{}_low_sun.dds", size)),
                          envtest::SkyBc6hCube(size, glm::dvec3(-0.7, 0.2, 0.1)));
    }
    const std::string bytes = envtest::Dds8BitCube(32, {kAllCubeFaces.begin(), kAllCubeFaces.end()},
                                                   [](CubeFace face, int x, int y) {
                                                     return std::array<std::uint8_t, 3>{
                                                         static_cast<std::uint8_t>(8 * x),
                                                         static_cast<std::uint8_t>(6 * y + 20),
                                                         static_cast<std::uint8_t>(30 * static_cast<int>(face) + 9)};
                                                   });
    for (int copy = 0; copy < 2; ++copy) envtest::WriteBytes(add(fmt::format("cube8_{}.dds", copy)), bytes);
    SkyParams params;
    params.sun_azimuth_degrees = 50.0;
    EXPECT_EQ(WriteCrossExr(MakeSky(32, params), add("sky_cross.exr")).message(), "");
    Image latlong(2 * kLatLongFaceSize, kLatLongFaceSize);
    for (int y = 0; y < latlong.height; ++y) {
      for (int x = 0; x < latlong.width; ++x) {
        latlong.at(x, y) = glm::vec3(1.0f + 0.02f * x, 0.5f + 0.05f * y, 2.0f - 0.01f * x);
      }
    }
    EXPECT_TRUE(envtest::WriteFloatImage(add("latlong.hdr"), latlong));
    envtest::WritePfm(add("latlong.pfm"), latlong);
    return inputs;
  }
  std::string Input(const std::string& name) const { return (Path("in") / name).string(); }

  // What `irrmap FILE --coefficients-only --order order2` gives (the batch's program: the nine
  // terms, the level by --max-error alone), as the batch's "level" and "coefficients".
  nlohmann::json SingleFileRun(const std::string& input) {
    IrrmapOptions options;
    options.environment = input;
    options.face_size = kLatLongFaceSize;
    options.order = ShOrder::kOrder2;
    options.coefficients_only = true;
    options.threads = 1;
    options.out_dir = Path("single");
    IrrmapReport report;
    const Status error = RunIrrmap(options, report);
    EXPECT_EQ(error.message(), "") << input;
    nlohmann::json coefficients = nlohmann::json::array();
    for (const glm::dvec3& c : report.coefficients.coefficients) coefficients.push_back({c.r, c.g, c.b});
    return {{"level", report.level}, {"coefficients", coefficients}};
  }
};

TEST_F(BatchConcurrency, EveryRecordAtAnyThreadCountIsTheSingleFileResult) {
  const std::vector<std::string> inputs = WriteInputs();
  std::map<std::string, nlohmann::json> single;
  for (const std::string& input : inputs) single[input] = SingleFileRun(input);

  for (int threads : {1, 2, 4, 8}) {
    BatchOptions options;
    options.inputs = {Input("*")};
    options.output = Path(fmt::format("threads{}.jsonl", threads));
    options.threads = threads;
    options.face_size = kLatLongFaceSize;
    BatchSummary summary;
    ASSERT_EQ(RunBatch(options, summary).message(), "");
    EXPECT_TRUE(summary.failures.empty()) << summary.failures.front().input << ": " << summary.failures.front().reason;
    const std::map<std::string, nlohmann::json> records = Records(options.output);
    ASSERT_EQ(records.size(), inputs.size()) << threads << " threads";
    for (const auto& [input, record] : records) {
      const std::string what = fmt::format("{} at --threads {}", fs::path(input).filename().string(), threads);
      ASSERT_EQ(single.count(input), 1u) << what;
      EXPECT_EQ(record["level"], single[input]["level"]) << what;
      EXPECT_LE(CoefficientDifference(record["coefficients"], single[input]["coefficients"]), kCoefficientTolerance)
          << what;
    }
  }
}

// ---- SIGKILL and --resume --------------------------------------------------------------------

// Starts `irrmap batch ARGS...` with stdout and stderr to `log`; returns its process id.
pid_t StartBatch(const std::vector<std::string>& args, const fs::path& log) {
  const std::string tool = std::string(VS11_BINARY_DIR) + "/irradiance/irrmap";
  std::vector<std::string> argv_text = {tool, "batch"};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::fflush(stdout);  // else the child's freopen writes what this process had buffered
  const pid_t pid = fork();
  if (pid == 0) {
    FILE* out = std::freopen(log.c_str(), "w", stdout);
    if (out == nullptr || dup2(fileno(stdout), STDERR_FILENO) < 0) _exit(127);
    std::vector<char*> argv;
    for (std::string& arg : argv_text) argv.push_back(arg.data());
    argv.push_back(nullptr);
    execv(tool.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

// The exit status of `pid`, or -signal when a signal ended it.
int Wait(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1000;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

TEST_F(BatchConcurrency, KilledAndResumedRunsLoseNothingAndDuplicateNothing) {
  const std::vector<std::string> inputs = WriteInputs();
  envtest::WriteBytes(Input("broken.dds"), std::string("DDS ") + std::string(40, '\x01'));
  const std::vector<std::string> common = {Input("*"), "--threads", "2", "--face-size",
                                           std::to_string(kLatLongFaceSize)};
  const auto args = [&](const fs::path& output, bool resume) {
    std::vector<std::string> all = common;
    all.insert(all.end(), {"-o", output.string()});
    if (resume) all.push_back("--resume");
    return all;
  };

  // The uninterrupted run, timed, for the values and for where to kill.
  const auto start = std::chrono::steady_clock::now();
  ASSERT_EQ(Wait(StartBatch(args(Path("whole.jsonl"), false), Path("whole.log"))), 1)
      << envtest::ReadBytes(Path("whole.log"));
  const double whole_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::map<std::string, nlohmann::json> whole = Records(Path("whole.jsonl"));
  ASSERT_EQ(whole.size(), inputs.size());

  // Kill at random moments of a run's length, at most kKills times or for about kBudget, then let
  // the last run finish. A kill after a run finished on its own just finds it done.
  constexpr int kKills = 25;
  constexpr double kBudgetSeconds = 15.0;
  std::mt19937 random(std::random_device{}());
  std::uniform_real_distribution<double> moment(0.0, whole_seconds);
  const fs::path output = Path("resumed.jsonl");
  int killed = 0;
  const auto kill_start = std::chrono::steady_clock::now();
  for (int attempt = 0; attempt < kKills; ++attempt) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - kill_start).count() > kBudgetSeconds) break;
    const pid_t pid = StartBatch(args(output, true), Path("run.log"));
    std::this_thread::sleep_for(std::chrono::duration<double>(moment(random)));
    kill(pid, SIGKILL);
    const int status = Wait(pid);
    if (status == -SIGKILL) ++killed;
    ASSERT_TRUE(status == -SIGKILL || status == 1) << status << "\n" << envtest::ReadBytes(Path("run.log"));
    // A run that finished before the first kill leaves nothing for later runs to do (they would
    // finish at once): start the output over, so that a kill lands on a run with work to lose.
    if (status == 1 && killed == 0) fs::remove(output);
  }
  const int final_status = Wait(StartBatch(args(output, true), Path("final.log")));
  const std::string final_log = envtest::ReadBytes(Path("final.log"));
  EXPECT_EQ(final_status, 1) << final_log;
  EXPECT_NE(final_log.find("skipped " + Input("broken.dds")), std::string::npos) << final_log;
  EXPECT_GT(killed, 0);

  const std::map<std::string, nlohmann::json> resumed = Records(output);  // fails on a duplicate
  EXPECT_EQ(resumed.size(), whole.size()) << killed << " kills";
  for (const auto& [input, record] : whole) {
    ASSERT_EQ(resumed.count(input), 1u) << input << " lost after " << killed << " kills";
    EXPECT_EQ(resumed.at(input)["level"], record["level"]) << input;
    EXPECT_LE(CoefficientDifference(resumed.at(input)["coefficients"], record["coefficients"]), kCoefficientTolerance)
        << input;
  }
  EXPECT_EQ(resumed.count(Input("broken.dds")), 0u);
}

// A requeued job while the old one still runs: the output's lock lets one of them write, and the
// other ends at once (status 1) naming the holder; neither duplicates a record, and a third run finds
// every input done.
TEST_F(BatchConcurrency, TwoResumeRunsStartedAtOnceWriteEveryInputOnce) {
  const std::vector<std::string> inputs = WriteInputs();
  const fs::path output = Path("both.jsonl");
  const std::vector<std::string> args = {Input("*"), "--threads", "2", "--face-size", std::to_string(kLatLongFaceSize),
                                         "-o", output.string(), "--resume"};
  const pid_t first = StartBatch(args, Path("first.log"));
  const pid_t second = StartBatch(args, Path("second.log"));
  const std::array<int, 2> statuses = {Wait(first), Wait(second)};
  const std::array<std::string, 2> logs = {envtest::ReadBytes(Path("first.log")), envtest::ReadBytes(Path("second.log"))};
  for (int run = 0; run < 2; ++run) {
    if (statuses[run] == 0) continue;
    EXPECT_EQ(statuses[run], 1) << logs[run];
    // The holder is named by its pid, or (when it has locked but not yet written its line, which
    // output_lock.cc waits for only briefly) said to be a process that has not written it yet.
    EXPECT_NE(logs[run].find(output.string() + " is in use by another irrmap batch: "), std::string::npos) << logs[run];
    EXPECT_TRUE(logs[run].find("batch: pid ") != std::string::npos ||
                logs[run].find("batch: a process that has not yet written its pid") != std::string::npos)
        << logs[run];
  }
  EXPECT_TRUE(statuses[0] == 0 || statuses[1] == 0) << logs[0] << logs[1];
  EXPECT_EQ(Records(output).size(), inputs.size());  // Records fails on a duplicate

  const int third = Wait(StartBatch(args, Path("third.log")));
  const std::string third_log = envtest::ReadBytes(Path("third.log"));
  EXPECT_EQ(third, 0) << third_log;
  EXPECT_NE(third_log.find(fmt::format("0 written to {}, {} already there", output.string(), inputs.size())),
            std::string::npos)
      << third_log;
  EXPECT_EQ(Records(output).size(), inputs.size());
  EXPECT_FALSE(fs::exists(fs::path(output) += ".lock")) << "the lock file outlived the runs";
}

}  // namespace
}  // namespace vs11::irradiance
