// Writing through a temporary beside the target: what a reader sees, and what a failure leaves.
#include "vm/core/atomic_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

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
  ASSERT_FALSE(WriteFileAtomically(dir_ / "out.txt", std::string_view("first")));
  ASSERT_FALSE(WriteFileAtomically(dir_ / "out.txt", std::string_view("second")));
  EXPECT_EQ(Read(dir_ / "out.txt"), "second");
  EXPECT_EQ(Entries(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, WriteIntoAMissingFolderFailsNamingThePath) {
  const fs::path path = dir_ / "missing" / "out.txt";
  const std::optional<std::string> error = WriteFileAtomically(path, std::string_view("x"));
  ASSERT_TRUE(error);
  EXPECT_NE(error->find(path.string()), std::string::npos) << *error;
  EXPECT_TRUE(Entries().empty());
}

TEST_F(AtomicFileTest, WriteOverAFolderFailsAndLeavesTheFolderAndNoTemporary) {
  fs::create_directories(dir_ / "taken");
  const std::optional<std::string> error = WriteFileAtomically(dir_ / "taken", std::string_view("x"));
  ASSERT_TRUE(error);
  EXPECT_NE(error->find((dir_ / "taken").string()), std::string::npos) << *error;
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
  const std::optional<std::string> error = CommitRenames(renames, &renamed);
  ASSERT_TRUE(error);
  EXPECT_NE(error->find((dir_ / "b.txt").string()), std::string::npos) << *error;
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
  EXPECT_FALSE(CommitRenames(renames, &renamed));
  EXPECT_EQ(renamed, (std::vector<fs::path>{dir_ / "x.json", dir_ / "y.json"}));
  EXPECT_EQ(Entries(), (std::vector<std::string>{"x.json", "y.json"}));
}

}  // namespace
}  // namespace vs11
