// The page from the command line: a stated scale with its unit, the scale bar and north arrow, the sheet of views,
// and the combinations refused as usage errors.

#include <gtest/gtest.h>

#include <string>

#include "cli_test_support.h"

namespace pcsketch {
namespace {

using test::CommandRun;
using test::slurp;
using CliPage = test::CliTest;

const std::string kBunny = PCSKETCH_DATA "/bunny.ply";

TEST_F(CliPage, RefusesAScaleItCannotKeep) {
  const std::string draw = "-q draw " + kBunny + " -o " + path("a.svg") + " ";
  const std::pair<std::string, std::string> cases[] = {
      {"--scale 1:20", "--units"},
      {"--scale 20 --units mm", "1:20"},
      {"--scale 1:20 --units mm --perspective", "orthographic"},
      {"--scale-bar --perspective", "orthographic"},
      {"--scale 1:20 --units mm --page-width-mm 100", "--page-width-mm"},
      {"--units inch", "--units"},
      {"--sheet third --view top", "--view"},
      {"--sheet third --views front,top", "--views"},
      {"--sheet third --perspective", "--perspective"},
      {"--sheet second", "--sheet"},
      {"--sheet first --stages " + path("st"), "--sheet"},
  };
  for (const auto& [flags, named] : cases) {
    const CommandRun r = run(draw + flags);
    EXPECT_EQ(r.status, 1) << flags << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << flags << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("a.svg"))) << flags;
  }
}

TEST_F(CliPage, ScaleSizesThePageInMillimetres) {
  // The bunny sample is in metres; at 1:1 its page is as wide as the framed view, at 1:10 a tenth of it.
  ASSERT_EQ(run("-q draw " + kBunny + " -o " + path("a.svg") + " --scale 1:1 --units m").status, 0);
  ASSERT_EQ(run("-q draw " + kBunny + " -o " + path("b.svg") + " --scale 1:10 --units m --scale-bar --north-arrow")
                .status,
            0);
  const auto page_width = [](const std::string& svg) {
    const std::size_t at = svg.find("width=\"", svg.find("<svg"));
    return std::stod(svg.substr(at + 7));
  };
  const std::string a = slurp(path("a.svg")), b = slurp(path("b.svg"));
  EXPECT_NE(a.find("mm\" height="), std::string::npos);
  EXPECT_NEAR(page_width(b) * 10, page_width(a), 1e-2 * page_width(a));
  EXPECT_EQ(a.find("8 annotations"), std::string::npos) << "no band without a bar or an arrow";
  EXPECT_NE(b.find("8 annotations"), std::string::npos);
  EXPECT_NE(b.find(">1:10</text>"), std::string::npos);
  EXPECT_NE(b.find(">N</text>"), std::string::npos);
}

TEST_F(CliPage, SheetHasFourNamedViewsOnOnePage) {
  const CommandRun r =
      run("-q draw " + kBunny + " --up 0,1,0 --size 300x200 --sheet first -o " + path("s.svg") + " -o " + path("s.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string svg = slurp(path("s.svg"));
  EXPECT_NE(svg.find("viewBox=\"0 0 600 400\""), std::string::npos);
  for (const char* name : {">FRONT<", ">TOP<", ">LEFT<", ">ISO<", ">first-angle projection<"})
    EXPECT_NE(svg.find(name), std::string::npos) << name;
  EXPECT_TRUE(std::filesystem::exists(path("s.png")));
}

TEST_F(CliPage, SheetReplaysFromItsSvgAndJson) {
  const std::string draw = "-q draw " + kBunny + " ";
  ASSERT_EQ(run(draw + "--sheet third --size 200x200 --scale-bar -o " + path("s.svg") + " --json " + path("s.json"))
                .status,
            0);
  for (const char* recorded : {"s.svg", "s.json"}) {
    const CommandRun r = run(draw + "--config " + path(recorded) + " -o " + path("again.svg"));
    ASSERT_EQ(r.status, 0) << recorded << ": " << r.err;
    EXPECT_EQ(slurp(path("again.svg")), slurp(path("s.svg"))) << recorded;
  }
  // A flag choosing a view draws that one view instead.
  ASSERT_EQ(run(draw + "--config " + path("s.svg") + " --view top -o " + path("top.svg")).status, 0);
  EXPECT_EQ(slurp(path("top.svg")).find(">FRONT<"), std::string::npos);
}

}  // namespace
}  // namespace pcsketch
