// Writing through a temporary beside the target: what a reader sees, and what a failure leaves.
#include "vm/core/atomic_file.h"

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

namespace vs11 {
namespace {

namespace fs = std::filesystem;

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("atomic_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> Entries() const {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }
  static std::string Read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, TemporaryIsHiddenBesideTheTargetWithItsExtensionAndNeverRepeats) {
  std::set<fs::path> seen;
  for (int i = 0; i < 100; ++i) {
    const fs::path temporary = TemporaryPathBeside(dir_ / "map.exr");
    EXPECT_EQ(temporary.parent_path(), dir_);
    EXPECT_EQ(temporary.filename().string().front(), '.');
    EXPECT_EQ(temporary.extension(), ".exr");
    EXPECT_TRUE(seen.insert(temporary).second) << temporary;
  }
}

TEST_F(AtomicFileTest, WriteReplacesTheFileAndLeavesNoTemporary) {
  ASSERT_TRUE(WriteFileAtomically(dir_ / "out.txt", std::string_view("first")).ok());
  ASSERT_TRUE(WriteFileAtomically(dir_ / "out.txt", std::string_view("second")).ok());
  EXPECT_EQ(Read(dir_ / "out.txt"), "second");
  EXPECT_EQ(Entries(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, WriteIntoAMissingFolderFailsNamingThePath) {
  const fs::path path = dir_ / "missing" / "out.txt";
  const Status error = WriteFileAtomically(path, std::string_view("x"));
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kCannotWriteFile);
  EXPECT_NE(error.message().find(path.string()), std::string::npos) << error.message();
  EXPECT_TRUE(Entries().empty());
}

TEST_F(AtomicFileTest, WriteOverAFolderFailsAndLeavesTheFolderAndNoTemporary) {
  fs::create_directories(dir_ / "taken");
  const Status error = WriteFileAtomically(dir_ / "taken", std::string_view("x"));
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find((dir_ / "taken").string()), std::string::npos) << error.message();
  EXPECT_EQ(Entries(), std::vector<std::string>{"taken"});
  EXPECT_TRUE(fs::is_directory(dir_ / "taken"));
}

TEST_F(AtomicFileTest, CommitStopsAtTheFirstFailureAndRemovesTheTemporariesLeft) {
  std::vector<PendingRename> renames;
  for (const char* name : {"a.txt", "b.txt", "c.txt"}) {
    const fs::path temporary = TemporaryPathBeside(dir_ / name);
    std::ofstream(temporary) << name;
    renames.push_back({temporary, dir_ / name});
  }
  fs::create_directories(dir_ / "b.txt" / "inside");  // a non-empty folder cannot be renamed over
  std::vector<fs::path> renamed;
  const Status error = CommitRenames(renames, &renamed);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find((dir_ / "b.txt").string()), std::string::npos) << error.message();
  EXPECT_EQ(renamed, std::vector<fs::path>{dir_ / "a.txt"});
  EXPECT_EQ(Read(dir_ / "a.txt"), "a.txt");
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a.txt", "b.txt"}));  // c's temporary is gone
}

TEST_F(AtomicFileTest, CommitRenamesEveryFileAndReportsThemInOrder) {
  std::vector<PendingRename> renames;
  for (const char* name : {"x.json", "y.json"}) {
    const fs::path temporary = TemporaryPathBeside(dir_ / name);
    std::ofstream(temporary) << name;
    renames.push_back({temporary, dir_ / name});
  }
  std::vector<fs::path> renamed;
  EXPECT_TRUE(CommitRenames(renames, &renamed).ok());
  EXPECT_EQ(renamed, (std::vector<fs::path>{dir_ / "x.json", dir_ / "y.json"}));
  EXPECT_EQ(Entries(), (std::vector<std::string>{"x.json", "y.json"}));
}

// Runs `body` in a child process and returns its wait status; the child never returns into the test.
template <class Body>
int InChild(Body body) {
  const pid_t child = ::fork();
  if (child == 0) {
    body();
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  return status;
}

// A PID that was a process a moment ago and is none now.
pid_t DeadPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

class AtomicFileSignalTest : public AtomicFileTest, public ::testing::WithParamInterface<int> {};

TEST_P(AtomicFileSignalTest, ASignalWhileWritingLeavesNoTemporaryAndStillEndsTheProcess) {
  const int signal = GetParam();
  const int status = InChild([&] {
    RemoveTemporariesOnSignals();
    const fs::path temporary = TemporaryPathBeside(dir_ / "map.exr");
    std::ofstream(temporary) << "half of a file";
    ::raise(signal);
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), signal);
  EXPECT_TRUE(Entries().empty());
}

INSTANTIATE_TEST_SUITE_P(InterruptAndTerminate, AtomicFileSignalTest, ::testing::Values(SIGINT, SIGTERM));

TEST_F(AtomicFileTest, ASignalAfterTheRenameLeavesTheFinishedFile) {
  const int status = InChild([&] {
    RemoveTemporariesOnSignals();
    if (!WriteFileAtomically(dir_ / "done.txt", std::string_view("done")).ok()) ::_exit(3);
    ::raise(SIGTERM);
  });
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(Entries(), std::vector<std::string>{"done.txt"});
}

TEST_F(AtomicFileTest, StaleTemporaryOfADeadProcessIsRemovedByTheNextWrite) {
  using namespace std::chrono_literals;
  const pid_t dead = DeadPid();
  const std::string stale = fmt::format(".map.exr.tmp-{}-0badc0de-0.exr", dead);
  const std::string fresh = fmt::format(".map.exr.tmp-{}-0badc0de-1.exr", dead);
  const std::string living = fmt::format(".map.exr.tmp-{}-0badc0de-2.exr", ::getppid());
  const std::string someone_elses = ".map.exr.tmp-backup";
  for (const std::string& name : {stale, fresh, living, someone_elses}) std::ofstream(dir_ / name) << "x";
  for (const std::string& name : {stale, living, someone_elses}) {
    fs::last_write_time(dir_ / name, fs::file_time_type::clock::now() - kStaleTemporaryAge - 1min);
  }
  ASSERT_TRUE(WriteFileAtomically(dir_ / "out.txt", std::string_view("new")).ok());
  // A fresh one may be another machine's, writing into a shared folder: its PID means nothing here.
  std::vector<std::string> kept = {fresh, living, someone_elses, "out.txt"};
  std::sort(kept.begin(), kept.end());
  EXPECT_EQ(Entries(), kept);
}

TEST_F(AtomicFileTest, AFailedWriteOfSeveralFilesLeavesNoneOfThem) {
  const std::string small(100, 's');
  const std::string large(64 << 10, 'l');
  std::ofstream(dir_ / "b.bin") << "old";
  // A full disk: the second file cannot grow past the limit (SIGXFSZ ignored: write fails instead).
  const int status = InChild([&] {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{16 << 10, 16 << 10};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const FileToWrite files[] = {{dir_ / "a.bin", small}, {dir_ / "b.bin", large}, {dir_ / "c.bin", small}};
    const Status error = WriteFilesAtomically(files);
    ::_exit(!error.ok() && error.message().find("b.bin") != std::string::npos ? 0 : 1);
  });
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(Entries(), std::vector<std::string>{"b.bin"});
  EXPECT_EQ(Read(dir_ / "b.bin"), "old");
}

TEST_F(AtomicFileTest, SeveralFilesAllLand) {
  const FileToWrite files[] = {{dir_ / "a.txt", "a"}, {dir_ / "b.txt", "b"}};
  ASSERT_TRUE(WriteFilesAtomically(files).ok());
  EXPECT_EQ(Entries(), (std::vector<std::string>{"a.txt", "b.txt"}));
  EXPECT_EQ(Read(dir_ / "b.txt"), "b");
}

}  // namespace
}  // namespace vs11
