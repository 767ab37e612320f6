#include "pcsketch/core/atomic_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "pcsketch/core/error.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test, removed afterwards.
class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pcsketch_atomic_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path path(const std::string& name) const { return dir_ / name; }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::size_t entries() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

TEST_F(AtomicFile, AFailedWriteLeavesTheFileAsItWasAndNoTemporary) {
  std::ofstream(path("out.json")) << "old";
  {
    TempFile temp(path("out.json"));
    std::ofstream(temp.path()) << "half a new fi";
  }  // destroyed without commit(), as when the writer throws
  EXPECT_EQ(read(path("out.json")), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(AtomicFile, CommitReplacesTheFileASymlinkPointsToAndKeepsTheLink) {
  std::ofstream(path("real.json")) << "old";
  fs::create_symlink("real.json", path("link.json"));
  TempFile temp(path("link.json"));
  EXPECT_EQ(temp.path().parent_path(), dir_);
  std::ofstream(temp.path()) << "new";
  temp.commit();
  EXPECT_TRUE(fs::is_symlink(path("link.json")));
  EXPECT_EQ(read(path("real.json")), "new");
  EXPECT_EQ(entries(), 2u);
}

TEST_F(AtomicFile, ADeviceOrADirectoryIsNeverReplaced) {
  // As root a rename over /dev/null would succeed: the constructor must refuse before creating anything there.
  fs::create_symlink("/dev/null", path("null.ply"));
  fs::create_directory(path("dir.ply"));
  for (const char* name : {"null.ply", "dir.ply"}) {
    SCOPED_TRACE(name);
    EXPECT_THROW(check_writable(path(name)), Error);
    try {
      TempFile temp(path(name));
      ADD_FAILURE() << "created " << temp.path();
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path(name).string() + ": exists and is not a regular file"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_TRUE(fs::is_symlink(path("null.ply")));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST_F(AtomicFile, CheckWritableNamesAMissingDirectory) {
  EXPECT_NO_THROW(check_writable(path("new.ply")));
  try {
    check_writable(path("no/such/new.ply"));
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), path("no/such/new.ply").string() + ": the directory " +
                                         path("no/such").string() + " does not exist");
  }
}

}  // namespace
}  // namespace pcsketch
