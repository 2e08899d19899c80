#include "output/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tests/output/output_test_util.h"

namespace wl {
namespace {

using test::count_entries;
using test::read_text;
using test::ScratchDir;

TEST(AtomicFile, WritesContentAndLeavesNoTemporary) {
  ScratchDir dir;
  const auto path = dir / "a.txt";
  write_file_atomically(path, "first\n");
  write_file_atomically(path, std::string("second\0line\n", 12));  // replaces, binary-safe
  EXPECT_EQ(read_text(path), std::string("second\0line\n", 12));
  EXPECT_EQ(count_entries(dir.path()), 1);
}

TEST(AtomicFile, MissingFolderThrowsWithPathAndLeavesNothing) {
  ScratchDir dir;
  const auto path = dir / "no-such-folder" / "a.txt";
  try {
    write_file_atomically(path, "x");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  }
  EXPECT_EQ(count_entries(dir.path()), 0);
}

TEST(AtomicFile, UnwritableFolderThrowsWithPathAndLeavesNothing) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  ScratchDir dir;
  const auto locked = dir / "locked";
  std::filesystem::create_directory(locked);
  ::chmod(locked.c_str(), 0555);
  const auto path = locked / "a.txt";
  EXPECT_THROW(
      {
        try {
          write_file_atomically(path, "x");
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
          throw;
        }
      },
      std::runtime_error);
  ::chmod(locked.c_str(), 0755);
  EXPECT_EQ(count_entries(locked), 0);
}

TEST(AtomicFile, ParentIsAFileThrowsWithPath) {
  ScratchDir dir;
  write_file_atomically(dir / "plain", "x");
  const auto path = dir / "plain" / "a.txt";
  try {
    write_file_atomically(path, "x");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(count_entries(dir.path()), 1);
}

TEST(AtomicFile, FailedRenameRemovesTemporary) {
  ScratchDir dir;
  const auto path = dir / "occupied";
  std::filesystem::create_directory(path);
  std::filesystem::create_directory(path / "child");  // a non-empty folder cannot be replaced by a file
  try {
    write_file_atomically(path, "x");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(count_entries(dir.path()), 1);  // only the folder; no .tmp-<pid> left behind
}

TEST(AtomicOutputFile, CommitRenamesPartFile) {
  ScratchDir dir;
  const auto path = dir / "m.csv";
  {
    AtomicOutputFile f(path);
    f.write("a,b\n");
    f.flush();
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_EQ(read_text(f.part_path()), "a,b\n");
    f.write("1,2\n");
    f.commit();
    EXPECT_TRUE(f.committed());
    EXPECT_THROW(f.write("late"), std::runtime_error);
  }
  EXPECT_EQ(read_text(path), "a,b\n1,2\n");
  EXPECT_EQ(count_entries(dir.path()), 1);
}

TEST(AtomicOutputFile, WithoutCommitLeavesOnlyPartFile) {
  ScratchDir dir;
  const auto path = dir / "m.csv";
  {
    AtomicOutputFile f(path);
    f.write("a,b\n1,2\n");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(read_text(dir / "m.csv.part"), "a,b\n1,2\n");
  EXPECT_EQ(count_entries(dir.path()), 1);
}

TEST(AtomicOutputFile, MissingFolderThrowsWithPath) {
  ScratchDir dir;
  const auto path = dir / "missing" / "m.csv";
  try {
    AtomicOutputFile f(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(count_entries(dir.path()), 0);
}

}  // namespace
}  // namespace wl
