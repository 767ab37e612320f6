// A draw stopped in any stage (SIGINT, SIGTERM, or the hidden --cancel-at used here in their place) or failing while
// it writes leaves neither an output file nor a temporary one (issue 14).

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::slurp;
using CliCancel = test::CliTest;

/// The files of the test's directory other than the captured stdout and stderr.
std::vector<std::string> left_over(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name != "out" && name != "err") names.push_back(name);
  }
  return names;
}

TEST_F(CliCancel, StoppedInAnyStageExitsWith130AndWritesNothing) {
  const std::string draw = "draw " PCSKETCH_FIXTURES "/fandisk.off --size 128x128 --shadow both";
  for (const std::string stage : {"read", "neighbourhoods", "curvature", "ridge/valley detection", "boundaries",
                                  "scene", "contour points", "visibility", "shadows", "writing"}) {
    std::string outputs;
    for (const char* name : {"d.svg", "d.png", "d.pdf"}) outputs += " -o " + path(name);
    const CommandRun r = run(draw + outputs + " --json " + path("d.json") + " --cancel-at '" + stage + "'");
    EXPECT_EQ(r.status, 130) << stage << ": " << r.err;
    EXPECT_EQ(r.err, "pcsketch: cancelled\n") << stage;
    EXPECT_EQ(left_over(dir_), std::vector<std::string>{}) << stage;
  }
}

TEST_F(CliCancel, AFailedWriteLeavesNoOutputAndNoTemporary) {
  // Under a 2 KB file size limit every output fails part-way (SIGXFSZ ignored: write() reports EFBIG instead).
  std::string outputs;
  for (const char* name : {"d.svg", "d.png", "d.pdf"}) outputs += " -o " + path(name);
  const std::string command = "sh -c \"trap '' XFSZ; ulimit -f 4; exec " + std::string(PCSKETCH_CLI) +
                              " -q draw " PCSKETCH_FIXTURES "/fandisk.off --size 600x600" + outputs + " --json " +
                              path("d.json") + "\" >" + path("out") + " 2>" + path("err");
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw));
  EXPECT_EQ(WEXITSTATUS(raw), 2) << slurp(path("err"));
  EXPECT_EQ(left_over(dir_), std::vector<std::string>{});
}

}  // namespace
}  // namespace pcsketch
