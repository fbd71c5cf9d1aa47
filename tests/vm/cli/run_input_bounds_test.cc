// vs11 run's numbers that become addresses and its repeatable options, end to end through the
// built tool: a bad value is a usage error (exit 2) or a bad file (exit 1), never a read outside the
// data; and the outputs stream, so a run completes under an address-space limit its CSV text
// would exceed.
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "vm/mesh/npy.h"

namespace {

namespace fs = std::filesystem;
using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

class RunInputBounds : public vs11::testing::ToolFolderTest {
 protected:
  void SetUp() override {
    ToolFolderTest::SetUp();
    program_ = Write("mov.vsh", "vs_1_1\ndcl_position v0\nmov oPos, v0\n");
    std::string floats;
    for (int i = 0; i < 8; ++i) {
      const float value = static_cast<float>(i);
      floats.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
    buffer_ = Write("seq.bin", floats);
    csv_ = Write("a.csv", "0,0,1\n1,0,0\n");
  }
  CommandResult Run(const std::string& args) { return RunVs11("run " + program_ + " " + args); }
  std::string program_, buffer_, csv_;
};

TEST_F(RunInputBounds, ElementOffsetThatWrapsAroundIsAUsageError) {
  // offset + 4 * 4 wraps to 0: the old check passed, and vertex 0 was the 16 bytes before the buffer.
  CommandResult r = Run("--buffer " + buffer_ + " --stride 16 --element v0=18446744073709551600:4");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("--element v0=18446744073709551600:4 ends past the 16-byte stride"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("oPos.x"), std::string::npos) << r.output;
  for (const char* element : {"v0=18446744073709551615:1", "v0=4611686018427387904:4", "v0=13:1", "v0=0:5"}) {
    CommandResult bad = Run("--buffer " + buffer_ + " --stride 16 --element " + element);
    EXPECT_EQ(bad.status, 2) << element << "\n" << bad.output;
    EXPECT_EQ(bad.output.find("oPos.x"), std::string::npos) << bad.output;
  }
  CommandResult stride = Run("--buffer " + buffer_ + " --stride 18446744073709551615 --element v0=0:4");
  EXPECT_EQ(stride.status, 2) << stride.output;
  CommandResult fine = Run("--buffer " + buffer_ + " --stride 16 --element v0=12:1");
  EXPECT_EQ(fine.status, 0) << fine.output;
  EXPECT_NE(fine.output.find("\n3,0,0,1\n7,0,0,1\n"), std::string::npos) << fine.output;
}

// CLI11 read -1 and 2^64 into a std::size_t as 2^64 - 1.
TEST_F(RunInputBounds, StrideAndTraceVerticesBeyondSizeTAreUsageErrors) {
  for (const char* value : {"-1", "18446744073709551616", "-16"}) {
    CommandResult stride = Run("--buffer " + buffer_ + " --stride " + value + " --element v0=0:4");
    EXPECT_EQ(stride.status, 2) << stride.output;
    EXPECT_NE(stride.output.find(std::string("--stride: '") + value + "' is not a whole number"), std::string::npos)
        << stride.output;
    CommandResult trace = Run("--input v0=" + csv_ + " --trace 0," + value);
    EXPECT_EQ(trace.status, 2) << trace.output;
    EXPECT_NE(trace.output.find(std::string("--trace: '") + value + "' is not a whole number"), std::string::npos)
        << trace.output;
  }
}

TEST_F(RunInputBounds, EveryRegisterGivenTwiceIsAUsageError) {
  vs11::mesh::NpyArray array;
  array.rows = 2;
  array.columns = 2;
  array.values = {0, 0, 1, 1};
  const std::vector<std::uint8_t> bytes = vs11::mesh::FormatNpy(array);
  const std::string npy = Write("p.npy", std::string(bytes.begin(), bytes.end()));
  const struct {
    std::string args;
    std::string message;
  } cases[] = {
      {"--buffer " + buffer_ + " --stride 16 --element v0=0:4 --element v0=0:2", "--element v0 is given twice"},
      {"--buffer " + buffer_ + " --stride 16 --element v1=0:4 --element V1=8:2", "--element v1 is given twice"},
      {"--input v0=" + csv_ + " --input v0=" + csv_, "--input v0 is given twice"},
      {"--input v2=" + csv_ + " --input v0=" + csv_ + " --input V2=" + csv_ + ":x", "--input v2 is given twice"},
      {"--npy v0=" + npy + " --npy v0=" + npy, "--npy v0 is given twice"},
      {"--input v0=" + csv_ + " --const c4=1,2,3,4 --const c4=0,0,0,0", "--const c4 is given twice"},
  };
  for (const auto& c : cases) {
    CommandResult r = Run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
  }
  // Different registers, and a --const over a --consts file, are fine.
  const std::string consts = Write("c.vsh", "def c4, 1, 2, 3, 4\n");
  CommandResult ok = Run("--input v0=" + csv_ + " --input v1=" + csv_ + " --consts " + consts + " --const c4=0,0,0,0");
  EXPECT_EQ(ok.status, 0) << ok.output;
}

TEST_F(RunInputBounds, InputThatIsNotARegularFileSaysWhatItIs) {
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& args : {"--mesh " + fifo.string(), "--npy v0=" + fifo.string(),
                                  "--buffer " + fifo.string() + " --stride 16 --element v0=0:4"}) {
    CommandResult r = Run(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(fifo.string() + ": is a named pipe (FIFO), not a regular file"), std::string::npos) << r.output;
  }
  CommandResult folder = Run("--mesh " + dir_.string());
  EXPECT_EQ(folder.status, 1) << folder.output;
  EXPECT_NE(folder.output.find("is a folder, not a regular file"), std::string::npos) << folder.output;
  CommandResult missing = Run("--buffer " + (dir_ / "none.bin").string() + " --stride 16 --element v0=0:4");
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find("none.bin: no such file"), std::string::npos) << missing.output;
}

TEST_F(RunInputBounds, ConstantRegisterBeyondAnyIntegerIsNamed) {
  CommandResult flag = Run("--input v0=" + csv_ + " --const c99999999999=1,2,3,4");
  EXPECT_EQ(flag.status, 2) << flag.output;
  EXPECT_NE(flag.output.find("c99999999999 is beyond every constant register"), std::string::npos) << flag.output;
  const std::string file = Write("big.vsh", "c4 = 1 2 3 4\ndef c4294967300, 1, 0, 0, 0\n");
  CommandResult consts = Run("--input v0=" + csv_ + " --consts " + file);
  EXPECT_EQ(consts.status, 1) << consts.output;
  EXPECT_NE(consts.output.find(file + ":2:5: error: c4294967300 is beyond every constant register"), std::string::npos)
      << consts.output;
}

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define VS11_SANITIZED_BUILD 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define VS11_SANITIZED_BUILD 1
#endif

// The tool under an address-space limit (prlimit, util-linux): a sanitizer's shadow memory alone
// is terabytes of address space, so the sanitized builds skip these.
CommandResult RunVs11Within(std::size_t megabytes, const std::string& args) {
  return vs11::testing::RunCommandLine("prlimit --as=" + std::to_string(megabytes << 20) + " " + VS11_BINARY_DIR +
                                       "/vm/vs11 " + args + " 2>&1");
}

std::size_t LineCount(const fs::path& file) {
  std::ifstream in(file);
  std::size_t lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

// 100000 vertices under 60 MB: the whole CSV as one string (and a vector of strings per row) was a
// bad_alloc and an abort; streamed, the run completes.
TEST_F(RunInputBounds, OutputsStreamUnderAnAddressSpaceLimit) {
#ifdef VS11_SANITIZED_BUILD
  GTEST_SKIP() << "a sanitizer needs more address space than the limit";
#endif
  const std::string program = Write("sphere.vsh", "vs_1_1\ndcl_normal v0\nmov oPos, v0\nmul oD0, v0, v0\n");
  const fs::path csv = dir_ / "x.csv";
  CommandResult r = RunVs11Within(60, "run " + program + " --sphere 100000 --threads 8 --out " + csv.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(LineCount(csv), 100001u);
  CommandResult files = RunVs11Within(60, "run " + program + " --sphere 100000 --out-npy " + (dir_ / "npy").string() +
                                              " --out-buffer " + (dir_ / "out.bin").string());
  ASSERT_EQ(files.status, 0) << files.output;
  EXPECT_EQ(fs::file_size(dir_ / "out.bin"), 100000u * 32);
  EXPECT_EQ(fs::file_size(dir_ / "npy/oPos.npy"), 128u + 100000u * 16);
}

// A CSV that cannot be written to stdout (a full disk) is a failure, not exit 0.
TEST_F(RunInputBounds, FailedWriteToStandardOutputIsAnError) {
  CommandResult r = Run("--input v0=" + csv_ + " >/dev/full");
  EXPECT_EQ(r.status, 1) << r.output;
}

// Where even the inputs do not fit: an error and exit 1, not an abort, and no file.
TEST_F(RunInputBounds, OutOfMemoryIsAnErrorAndLeavesNoFile) {
#ifdef VS11_SANITIZED_BUILD
  GTEST_SKIP() << "a sanitizer needs more address space than the limit";
#endif
  const std::string program = Write("sphere.vsh", "vs_1_1\ndcl_normal v0\nmov oPos, v0\n");
  CommandResult r = RunVs11Within(60, "run " + program + " --sphere 10000000 --out " + (dir_ / "x.csv").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("vs11: error: out of memory"), std::string::npos) << r.output;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find("x.csv"), std::string::npos) << entry.path();
  }
}

}  // namespace
