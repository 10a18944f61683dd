// isocurv lines, render --lines and run --lines end to end.
#include <gtest/gtest.h>

#include "tests/app/cli.h"

namespace isocurv::test {
namespace {

using json = nlohmann::json;

TEST(CliLines, VtpFromAVolumeWithJson) {
  TempDir dir("lines_vtp");
  const auto r =
      run_isocurv({"lines", dataset("torus"), "--lines", "all", "--view", "+x",
                   "-o", dir / "t.vtp", "--json", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "lines --json");
  EXPECT_EQ(j["lines"], "contours,suggestive,ridges,valleys");
  EXPECT_GT(j["segments"]["contours"].get<int>(), 50);
  EXPECT_GT(j["polylines"].get<int>(), 0);
  EXPECT_TRUE(j["timings_ms"].contains("lines")) << j.dump(2);
  EXPECT_FALSE(j["timings_ms"].contains("visibility"))
      << ".vtp keeps every line";
  EXPECT_EQ(j["segments_before_visibility"].get<int>(),
            j["segments"]["contours"].get<int>() +
                j["segments"]["suggestive"].get<int>() +
                j["segments"]["ridges"].get<int>() +
                j["segments"]["valleys"].get<int>());
  const std::string vtp = read_file(dir / "t.vtp");
  EXPECT_NE(vtp.find("LineType"), std::string::npos);
  EXPECT_NE(vtp.find("Strength"), std::string::npos);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.vtp"});
}

TEST(CliLines, SvgHoldsOnlyVisibleLinesAndMatchesTheReference) {
  TempDir dir("lines_svg");
  const auto r =
      run_isocurv({"lines", dataset("torus"), "--view", "+y", "--size",
                   "400x300", "-o", dir / "t.svg", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "lines --json");
  const int kept = j["segments"]["contours"].get<int>() +
                   j["segments"]["suggestive"].get<int>();
  EXPECT_GT(kept, 0);
  EXPECT_LT(kept, j["segments_before_visibility"].get<int>())
      << "the torus hides part of its own contours";
  const std::string svg = read_file(dir / "t.svg");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("width=\"400\" height=\"300\""), std::string::npos);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  // the C++ reference gives the same drawing up to float rounding: the same
  // counts within 1%
  const auto ref = run_isocurv({"lines", dataset("torus"), "--view", "+y",
                                "--size", "400x300", "-o", dir / "ref.svg",
                                "--json", "--device", "reference"});
  ASSERT_TRUE(ref.ok()) << ref.describe();
  const json k = parse_json(ref.out, "lines --json (reference)");
  EXPECT_NEAR(k["segments"]["contours"].get<double>(),
              j["segments"]["contours"].get<double>(),
              0.01 * j["segments"]["contours"].get<double>() + 2);
}

TEST(CliLines, RenderAndRunOverlayTheLines) {
  TempDir dir("lines_render");
  const auto plain =
      run_isocurv({"render", dataset("torus"), "--size", "200x150", "-o",
                   dir / "plain.png", "--quiet"});
  ASSERT_TRUE(plain.ok()) << plain.describe();
  const auto lined =
      run_isocurv({"render", dataset("torus"), "--size", "200x150", "--lines",
                   "contours,suggestive", "-o", dir / "lines.png", "--json"});
  ASSERT_TRUE(lined.ok()) << lined.describe();
  EXPECT_TRUE(
      parse_json(lined.out, "render --json")["timings_ms"].contains("lines"));
  EXPECT_EQ(png_size(dir / "lines.png")[0], 200u);
  EXPECT_NE(read_file(dir / "plain.png"), read_file(dir / "lines.png"));
  const auto run =
      run_isocurv({"run", dataset("torus"), "--size", "200x150", "--lines",
                   "contours,ridges", "-o", dir / "out", "--quiet"});
  ASSERT_TRUE(run.ok()) << run.describe();
  for (const char *f :
       {"torus.vtp", "torus.png", "torus-lines.vtp", "stats.json"})
    EXPECT_TRUE(fs::exists(dir / (std::string("out/") + f))) << f;
}

TEST(CliLines, MeshFileWithoutCurvatureIsEstimatedWithANote) {
  TempDir dir("lines_mesh");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "s.obj",
                           "--quiet"})
                  .ok());
  const auto r = run_isocurv({"lines", dir / "s.obj", "-o", dir / "s.svg"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.err.find("estimated"), std::string::npos) << r.describe();
  EXPECT_NE(r.out.find("wrote"), std::string::npos);
}

// prantl2, prantl3 and meyer give no directions or derivative: contours work, the other line
// types are refused in one line naming the estimator, before any output is written.
TEST(CliLines, EstimatorsWithoutDirectionsDrawContoursOnly) {
  TempDir dir("lines_prantl");
  for (const char *est : {"prantl2", "prantl3", "meyer"}) {
    const auto ok = run_isocurv({"lines", dataset("torus"), "--estimator", est, "--lines",
                                 "contours", "-o", dir / (std::string(est) + ".vtp"), "--json"});
    ASSERT_TRUE(ok.ok()) << ok.describe();
    EXPECT_GT(nlohmann::json::parse(ok.out)["segments"]["contours"].get<int>(), 50) << est;
    for (const char *sel : {"contours,suggestive", "ridges"}) {
      const auto r = run_isocurv({"lines", dataset("torus"), "--estimator", est, "--lines", sel,
                                  "-o", dir / "refused.vtp"});
      expect_clean_failure(r, est);
      expect_one_error_line(r, "only --lines contours");
    }
  }
  const auto r = run_isocurv({"render", dataset("torus"), "--estimator", "meyer", "--lines",
                              "ridges", "-o", dir / "refused.png"});
  expect_clean_failure(r, "meyer");
  EXPECT_FALSE(std::filesystem::exists(dir / "refused.vtp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "refused.png"));
}

TEST(CliLines, BadInput) {
  TempDir dir("lines_bad");
  expect_usage_error(run_isocurv({"lines", dataset("torus"), "--lines",
                                  "contours,bogus", "-o", dir / "t.vtp"}),
                     "--lines");
  expect_clean_failure(
      run_isocurv({"lines", dataset("torus"), "-o", dir / "t.png"}), "t.png");
  expect_usage_error(run_isocurv({"render", dataset("torus"), "--lines",
                                  "ridges,,valleys", "-o", dir / "r.png"}),
                     "--lines");
  EXPECT_TRUE(dir.entries().empty());
}

} // namespace
} // namespace isocurv::test
