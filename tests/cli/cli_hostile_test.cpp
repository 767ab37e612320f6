// Hostile command lines and the user's files (issue 10): every numeric flag with nan, inf, -1, 0 and 1e308 ends in
// exit 0 or 1 (never a signal or a hang); outputs are checked before the work and replaced only when complete.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;
using test::slurp;

/// Runs the binary with a time limit; `prefix` is shell run before it (ulimit, trap).
class CliHostile : public test::CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    // A small sphere: enough points for every stage to run, small enough for hundreds of runs.
    std::ofstream xyz(path("s.xyz"));
    const int n = 300;
    for (int i = 0; i < n; ++i) {
      const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), a = i * 2.399963229728653;
      xyz << r * std::cos(a) << " " << r * std::sin(a) << " " << z << "\n";
    }
  }
  CommandRun limited(const std::string& args, const std::string& prefix = "") const {
    const std::string command = "sh -c \"" + prefix + " exec timeout -s KILL 120 " + PCSKETCH_CLI + " " + args +
                                "\" >" + path("out") + " 2>" + path("err");
    const int raw = std::system(command.c_str());
    CommandRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.err = slurp(path("err"));
    return r;
  }
  std::string draw(const std::string& flags) const {
    return "draw " + path("s.xyz") + " --size 96x96 -o " + path("o.svg") + " " + flags;
  }
};

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST_F(CliHostile, EveryNumericFlagWithNanInfNegativeZeroAndHuge) {
  const std::vector<std::string> flags = {"--azimuth",
                                          "--elevation",
                                          "--fov",
                                          "--margin",
                                          "--neighbours",
                                          "--alpha",
                                          "--extreme-percentile",
                                          "--saliency-floor",
                                          "--median-factor",
                                          "--suppression-cone",
                                          "--radius",
                                          "--radius-abs",
                                          "--corridor",
                                          "--max-turn",
                                          "--join-distance",
                                          "--beta",
                                          "--min-length",
                                          "--min-length-abs",
                                          "--smooth",
                                          "--smooth-weight",
                                          "--z-max",
                                          "--contour-radius",
                                          "--contour-persistence",
                                          "--denoised-contour-length",
                                          "--boundary-gap",
                                          "--boundary-min-size",
                                          "--boundary-radius",
                                          "--outlier-density",
                                          "--outlier-min-cluster",
                                          "--denoise-trigger",
                                          "--denoise-iterations",
                                          "--denoise-passes",
                                          "--denoise-cutoff",
                                          "--self-offset",
                                          "--rho-min",
                                          "--rho-max",
                                          "--cofi",
                                          "--light-elevation",
                                          "--light-azimuth",
                                          "--shadow-d",
                                          "--shadow-k",
                                          "--hatch-spacing",
                                          "--fusion-distance",
                                          "--fusion-min-stretch",
                                          "--min-stroke-length",
                                          "--pen-width",
                                          "--pen-width-px",
                                          "--pen-width-mm",
                                          "--min-stroke-mm",
                                          "--merge-tolerance-mm",
                                          "--turntable",
                                          "--page-width-mm",
                                          "--max-memory",
                                          "--threads"};
  for (const std::string& flag : flags)
    for (const char* value : {"nan", "inf", "-1", "0", "1e308", "1e309"}) {
      SCOPED_TRACE(flag + " " + value);
      const bool plotter = flag == "--pen-width" || flag == "--pen-width-mm" || flag == "--min-stroke-mm" ||
                           flag == "--merge-tolerance-mm";
      const std::string extra = plotter ? " --plotter" : flag == "--fov" ? " --perspective" : "";
      const CommandRun r = limited(draw(flag + " " + value + extra));
      EXPECT_TRUE(r.status == 0 || r.status == 1) << r.status << ": " << r.err;
      EXPECT_LE(lines(r.err), 1u) << r.err;
      if (r.status == 1) {
        EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
      }
    }
  for (const char* flag : {"--view", "--up", "--light", "--eye", "--target"})
    for (const char* value : {"nan,0,0", "inf,1,1", "0,0,0", "1e308,1e308,1e308", "-1,-1,-1"}) {
      SCOPED_TRACE(std::string(flag) + " " + value);
      const CommandRun r = limited(draw(std::string(flag) + " " + value + " --perspective"));
      EXPECT_TRUE(r.status == 0 || r.status == 1) << r.status << ": " << r.err;
      EXPECT_LE(lines(r.err), 1u) << r.err;
    }
  for (const char* size : {"nan", "0x0", "-1x5", "40000x40000", "2x1000000000", "1e308x1", "20000x20000"}) {
    SCOPED_TRACE(size);
    const CommandRun r = limited("draw " + path("s.xyz") + " -o " + path("o.png") + " --size " + size);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
  }
}

TEST_F(CliHostile, BadValuesFailAtOnceNamingTheFlag) {
  // Embree aborted on a NaN light; --alpha 0 failed only after the whole computation; pen width nan was written.
  for (const std::string flags : {"--light-elevation nan", "--light-azimuth inf", "--contour-radius nan", "--alpha 0",
                                  "--plotter --pen-width nan", "--hatch-spacing 0.001",
                                  "--fusion-distance 1e9"}) {
    SCOPED_TRACE(flags);
    const CommandRun r = limited(draw(flags));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(flags.substr(flags.rfind("--"), flags.rfind(' ') - flags.rfind("--"))), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(path("o.svg")));
  }
  EXPECT_NE(limited(draw("--alpha 0")).err.find("--alpha: must be in (0, 1), got 0"), std::string::npos);
}

TEST_F(CliHostile, HugeViewDirectionGivesARealCamera) {
  const CommandRun r = limited(draw("--view 1e308,1e308,1e308 --json " + path("o.json")));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json camera = nlohmann::json::parse(slurp(path("o.json")))["camera"];
  ASSERT_TRUE(camera["direction"].is_array()) << camera.dump();
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(camera["direction"][a].get<double>(), 1 / std::sqrt(3.0), 1e-6);
}

TEST_F(CliHostile, OutputsAreCheckedBeforeTheWork) {
  EXPECT_EQ(limited(draw("-o " + path("x.gif"))).status, 1);
  const CommandRun missing = limited(draw("-o " + path("no/such/dir/x.svg")));
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.err.find("does not exist"), std::string::npos) << missing.err;
  // --stages would overwrite an -o output written moments before.
  fs::create_directories(path("st"));
  const CommandRun collide = limited(draw("-o " + path("st/b_contours.svg") + " --stages " + path("st")));
  EXPECT_EQ(collide.status, 1) << collide.err;
  EXPECT_NE(collide.err.find("--stages: would overwrite"), std::string::npos) << collide.err;
  EXPECT_FALSE(fs::exists(path("o.svg")));
  // --stages under a regular file: refused at once (was exit 3 after writing the -o files).
  std::ofstream(path("plain")) << "x";
  const CommandRun unwritable = limited(draw("--stages " + path("plain/st")));
  EXPECT_EQ(unwritable.status, 1) << unwritable.err;
  EXPECT_FALSE(fs::exists(path("o.svg")));
}

TEST_F(CliHostile, OverlongOutputNamesAreUsageErrors) {
  // Found by fuzz_cli: a --stages name over NAME_MAX made weakly_canonical throw, exit 3 "internal error".
  const std::string name(300, 'n');
  for (const std::string& flags :
       {"--stages " + path(name), "-o " + path(name + ".svg"), "--json " + path(name + ".json")}) {
    SCOPED_TRACE(flags.substr(0, 8));
    const CommandRun r = limited(draw(flags));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("File name too long"), std::string::npos) << r.err;
  }
  const CommandRun features = limited("-q features " + path("s.xyz") + " -o " + path(name + ".ply"));
  EXPECT_EQ(features.status, 1) << features.err;
  EXPECT_NE(features.err.find("--output: "), std::string::npos) << features.err;
}

TEST_F(CliHostile, SymlinkOutputReplacesItsTargetAndStays) {
  std::ofstream(path("real.svg")) << "old";
  fs::create_symlink(path("real.svg"), path("link.svg"));
  const CommandRun r = limited("draw " + path("s.xyz") + " --size 96x96 -o " + path("link.svg"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(path("link.svg")));
  EXPECT_NE(slurp(path("real.svg")).find("</svg>"), std::string::npos);
  // A symlink to a device is refused, not deleted.
  fs::create_symlink("/dev/full", path("full.png"));
  EXPECT_EQ(limited("draw " + path("s.xyz") + " -o " + path("full.png")).status, 1);
  EXPECT_TRUE(fs::is_symlink(path("full.png")));
}

TEST_F(CliHostile, FullDiskLeavesEarlierOutputsByteIdentical) {
  const std::string outputs =
      " -o " + path("d.svg") + " -o " + path("d.png") + " -o " + path("d.pdf") + " --json " + path("d.json");
  ASSERT_EQ(limited("draw " + path("s.xyz") + " --size 96x96" + outputs).status, 0);
  std::vector<std::string> before;
  for (const char* f : {"d.svg", "d.png", "d.pdf", "d.json"}) before.push_back(slurp(path(f)));
  // A different drawing (larger, another view) under a 4 KB file size limit: every write fails part-way. SIGXFSZ is
  // ignored so that write() reports EFBIG instead of killing the process.
  const CommandRun r =
      limited("draw -q " + path("s.xyz") + " --size 900x900 --azimuth 30" + outputs, "trap '' XFSZ; ulimit -f 4;");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  int i = 0;
  for (const char* f : {"d.svg", "d.png", "d.pdf", "d.json"}) EXPECT_EQ(slurp(path(f)), before[i++]) << f;
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(CliHostile, FeaturesAndSampleFullDiskLeaveEarlierOutputsByteIdentical) {
  const std::string outputs = " -o " + path("f.ply") + " --lines " + path("f.json");
  ASSERT_EQ(limited("-q features " + path("s.xyz") + outputs).status, 0);
  const std::string ply = slurp(path("f.ply")), json = slurp(path("f.json"));
  // ulimit -f counts 512-byte blocks in sh: 2 KB, less than the 300 points' PLY (about 11 KB binary).
  const std::string full_disk = "trap '' XFSZ; ulimit -f 4;";
  const CommandRun features = limited("-q features " + path("s.xyz") + " --ascii" + outputs, full_disk);
  EXPECT_EQ(features.status, 2) << features.err;
  EXPECT_EQ(lines(features.err), 1u) << features.err;
  EXPECT_NE(features.err.find(path("f.ply") + ": PLY writer: write failed"), std::string::npos) << features.err;
  const CommandRun sample =
      limited("-q sample " PCSKETCH_FIXTURES "/fandisk.off -n 2000 -o " + path("f.ply"), full_disk);
  EXPECT_EQ(sample.status, 2) << sample.err;
  EXPECT_EQ(slurp(path("f.ply")), ply);
  EXPECT_EQ(slurp(path("f.json")), json);
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(CliHostile, FeaturesAndSampleOutputsAreCheckedBeforeTheWork) {
  fs::create_symlink("/dev/full", path("full.ply"));
  fs::create_symlink("/dev/full", path("full.json"));
  const std::string features = "-q features " + path("s.xyz");
  for (const std::string& flags : {" -o " + path("full.ply"), " -o " + path("o.ply") + " --lines " + path("full.json"),
                                   " -o " + path("o.ply") + " --lines " + path("./o.ply"),
                                   " -o " + path("no/such/o.ply")}) {
    SCOPED_TRACE(flags);
    const CommandRun r = limited(features + flags);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_FALSE(fs::exists(path("o.ply")));
  }
  EXPECT_EQ(limited("-q sample " PCSKETCH_FIXTURES "/fandisk.off -n 100 -o " + path("full.ply")).status, 1);
  EXPECT_TRUE(fs::is_symlink(path("full.ply")));
  EXPECT_TRUE(fs::is_symlink(path("full.json")));
  // A link to a regular file: the file is replaced, the link kept.
  std::ofstream(path("real.ply")) << "old";
  fs::create_symlink(path("real.ply"), path("link.ply"));
  ASSERT_EQ(limited(features + " -o " + path("link.ply")).status, 0);
  EXPECT_TRUE(fs::is_symlink(path("link.ply")));
  EXPECT_EQ(slurp(path("real.ply")).substr(0, 4), "ply\n");
}

TEST_F(CliHostile, MemoryIsEstimatedFromTheImageAndThePointsBeforeTheAnalysis) {
  // 300 points at 256 + 28 x 16 bytes and a 96x96 image (9216 + 48384 bytes): 268800 bytes in all.
  const CommandRun over = limited(draw("--max-memory 0.0002687"));
  EXPECT_EQ(over.status, 1) << over.err;
  EXPECT_EQ(lines(over.err), 1u) << over.err;
  EXPECT_NE(over.err.find("--max-memory: " + path("s.xyz") +
                          ": 300 points (--neighbours 16) and a 96x96 image need about 0.000269 GB"),
            std::string::npos)
      << over.err;
  EXPECT_FALSE(fs::exists(path("o.svg")));
  EXPECT_EQ(limited(draw("--max-memory 0.0002689")).status, 0);
  // features has no image: 300 x 704 = 211200 bytes.
  const std::string features = "-q features " + path("s.xyz") + " -o " + path("f.ply") + " --max-memory ";
  const CommandRun refused = limited(features + "0.0002111");
  EXPECT_EQ(refused.status, 1) << refused.err;
  EXPECT_NE(refused.err.find("--max-memory: " + path("s.xyz") + ": 300 points"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(path("f.ply")));
  EXPECT_EQ(limited(features + "0.0002113").status, 0);
}

TEST_F(CliHostile, FifoInputIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo(path("p.xyz").c_str(), 0600), 0);
  const CommandRun r = limited("info " + path("p.xyz"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("not a regular file"), std::string::npos) << r.err;
}

TEST_F(CliHostile, CloudsAtImpossibleScalesAreBadInputNamingTheFile) {
  // Scaled by 1e30 or 1e-30, the sphere used to fail as "the mean spacing h must be positive", naming no file.
  for (const double scale : {1e30, 1e-30}) {
    std::ifstream in(path("s.xyz"));
    std::ofstream out(path("scaled.xyz"));
    double x = 0, y = 0, z = 0;
    while (in >> x >> y >> z) out << x * scale << " " << y * scale << " " << z * scale << "\n";
    out.close();
    const CommandRun r = limited("draw " + path("scaled.xyz") + " -o " + path("o.svg"));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(path("scaled.xyz") + ": the points span"), std::string::npos) << r.err;
  }
}

TEST_F(CliHostile, InfoNeighboursAreCapped) {
  EXPECT_EQ(limited("info " + path("s.xyz") + " --k 1000000").status, 1);
  EXPECT_EQ(limited("info " + path("s.xyz") + " --k 256").status, 0);
}

}  // namespace
}  // namespace pcsketch
