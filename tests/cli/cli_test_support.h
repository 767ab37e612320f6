#pragma once
// Runs the built pcsketch binary (PCSKETCH_CLI) with stdout/stderr captured, one temporary directory per test.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace pcsketch::test {

struct CommandRun {
  int status = -1;  ///< exit status, -1 if the process did not exit normally
  std::string out, err;
};

/// The whole file as bytes.
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Fixture: `run("draw …")` runs the binary; `path(name)` names a file in this test's own temporary directory.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / ("pcsketch_" + std::string(info->test_suite_name()) + "_" +
                                                     info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// `mem_available`: bytes to report as available memory (PCSKETCH_MEM_AVAILABLE); empty: the machine's.
  CommandRun run(const std::string& args, const std::string& mem_available = {}) const {
    const std::string env = mem_available.empty() ? "" : "PCSKETCH_MEM_AVAILABLE=" + mem_available + " ";
    const std::string command =
        env + std::string(PCSKETCH_CLI) + " " + args + " >" + path("out") + " 2>" + path("err");
    const int raw = std::system(command.c_str());
    CommandRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(dir_ / "out");
    r.err = slurp(dir_ / "err");
    return r;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

}  // namespace pcsketch::test
