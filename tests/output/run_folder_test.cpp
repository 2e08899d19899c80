// One run per output folder; a rerun removes what the old run left.
#include <gtest/gtest.h>

#include <fstream>

#include "output/run_folder.h"

namespace wl {
namespace {

namespace fs = std::filesystem;

class RunFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("weavelab_run_folder_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void touch(const fs::path& rel) {
    fs::create_directories((dir_ / rel).parent_path());
    std::ofstream(dir_ / rel) << "old";
  }
  static bool owned(const fs::path& rel) { return rel.filename().string().starts_with("mine"); }
  fs::path dir_;
};

TEST_F(RunFolderTest, CreatesTheFolderAndRefusesASecondHolder) {
  {
    RunFolder first(dir_, owned);
    EXPECT_TRUE(fs::is_directory(dir_));
    try {
      RunFolder second(dir_, owned);
      FAIL() << "two holders of one folder";
    } catch (const OutputFolderRefused& e) {
      EXPECT_NE(std::string(e.what()).find(dir_.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(::getpid())), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(RunFolder(dir_, owned));  // released with the first holder
}

TEST_F(RunFolderTest, RemovesOnlyTheOldRunsOwnFiles) {
  touch("mine.txt");
  touch("sub/mine_2.txt");
  touch("notes.txt");
  touch("sub/other.txt");
  { RunFolder f(dir_, owned); }
  EXPECT_FALSE(fs::exists(dir_ / "mine.txt"));
  EXPECT_FALSE(fs::exists(dir_ / "sub/mine_2.txt"));
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
  EXPECT_TRUE(fs::exists(dir_ / "sub/other.txt"));
}

TEST_F(RunFolderTest, ARefusedRunRemovesNothing) {
  RunFolder first(dir_, [](const fs::path&) { return false; });
  touch("mine.txt");
  EXPECT_THROW(RunFolder(dir_, owned), OutputFolderRefused);
  EXPECT_TRUE(fs::exists(dir_ / "mine.txt"));
}

TEST_F(RunFolderTest, AFileIsNoFolder) {
  std::ofstream(dir_) << "x";
  EXPECT_THROW(RunFolder(dir_, owned), OutputFolderRefused);
  fs::remove(dir_);
}

}  // namespace
}  // namespace wl
