// Usage errors and exit statuses (README, "Exit status"): 2 and one prefixed line for bad or
// missing arguments, 1 for bad input, the command list without arguments.
#include <gtest/gtest.h>

#include "cli.h"

using namespace isocurv::test;

namespace {
const char* const kCommands[] = {"info",   "extract", "curvature", "run",
                                 "render", "view",    "check",     "devices"};
}  // namespace

TEST(CliUsage, ParseErrorsAreOnePrefixedLineWithStatus2) {
  TempDir dir("usage");
  // CLI11's own messages were two lines without the prefix and exited with 104-114.
  expect_usage_error(run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--bogus"}),
                     "--bogus");
  expect_usage_error(run_isocurv({"extract", dataset("sphere")}), "--output");
  expect_usage_error(
      run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--iso", "abc"}), "--iso");
  expect_usage_error(run_isocurv({"info"}), "VOLUME");
  expect_usage_error(run_isocurv({"info", dataset("sphere"), "--dims", "1", "2"}), "--dims");
  expect_usage_error(
      run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--device", "gpu"}),
      "--device");
  expect_usage_error(run_isocurv({"--bogus"}), "--bogus");
  // The message says where to look.
  const auto r = run_isocurv({"render", dataset("sphere"), "-o", dir / "o.png", "--cmap", "Z"});
  expect_usage_error(r, "--cmap");
  EXPECT_NE(r.err.find("isocurv render --help"), std::string::npos) << r.describe();
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CliUsage, UnknownCommandIsAUsageError) {
  expect_usage_error(run_isocurv({"extrct", dataset("sphere"), "-o", "/nonexistent/o.vtp"}),
                     "extrct");
}

// Mistyped names get the closest one the command knows; nothing close, no guess.
TEST(CliUsage, MistypedNamesGetASuggestion) {
  TempDir dir("suggest");
  const auto colour =
      run_isocurv({"render", dataset("sphere"), "-o", dir / "o.png", "--colour", "H"});
  expect_usage_error(colour, "--colour");
  EXPECT_NE(colour.err.find("did you mean --color?"), std::string::npos) << colour.describe();
  const auto isovalue =
      run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--isovalue", "0.5"});
  expect_usage_error(isovalue, "--isovalue");
  EXPECT_NE(isovalue.err.find("did you mean --iso?"), std::string::npos) << isovalue.describe();
  const auto far = run_isocurv({"extract", dataset("sphere"), "-o", dir / "o.vtp", "--zzzzzz"});
  expect_usage_error(far, "--zzzzzz");
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.describe();
  const auto command = run_isocurv({"extrct", dataset("sphere"), "-o", dir / "o.vtp"});
  expect_usage_error(command, "extrct");
  EXPECT_NE(command.err.find("did you mean extract?"), std::string::npos) << command.describe();
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}

TEST(CliUsage, UnknownCommandListsEveryCommand) {
  // The list once named only the first eight commands.
  const auto r = run_isocurv({"frobnicate"});
  expect_usage_error(r, "frobnicate");
  for (const char* c : {"info", "extract", "check", "curvature", "run", "compare", "features",
                        "render", "view", "lines", "deform", "screen", "devices"})
    EXPECT_NE(r.err.find(std::string(" ") + c), std::string::npos) << c << "\n" << r.describe();
}

TEST(CliUsage, BadInputIsStatus1) {
  TempDir dir("input");
  expect_clean_failure(run_isocurv({"info", dir / "missing.nrrd"}), "missing.nrrd");
}

TEST(CliUsage, NoArgumentsListsTheCommandsWithStatus2) {
  const auto r = run_isocurv({}, 20);
  EXPECT_EQ(r.exit_code, 2) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.describe();
  for (const char* cmd : kCommands)
    EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd << "\n" << r.out;
}

TEST(CliUsage, HelpStatesTheExitStatuses) {
  const auto r = run_isocurv({"--help"}, 20);
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_NE(r.out.find("1 bad input"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 a usage error"), std::string::npos) << r.out;
}

// A fuzzing campaign passed "nan" through every range check (each comparison with NaN is false):
// a picture without a surface, an SVG without lines, a series naming a .pvd it never wrote.
// Every floating-point option now refuses NaN and infinities as a usage error, before any work.
TEST(CliUsage, NotANumberIsRefusedByEveryFloatOption) {
  TempDir dir("usage_nan");
  const std::string png = dir / "o.png";
  for (const std::vector<std::string>& opt :
       {std::vector<std::string>{"--roll", "nan"}, {"--elevation", "nan"}, {"--azimuth", "NaN"},
        {"--zoom", "nan"}, {"--percentile", "nan"}, {"--ao-scale", "nan"}, {"--dirs-length", "nan"},
        {"--zoom", "inf"}, {"--ao-scale", "-inf"}}) {
    std::vector<std::string> args = {"render", dataset("sphere"), "-o", png};
    args.insert(args.end(), opt.begin(), opt.end());
    expect_usage_error(run_isocurv(args), opt[0]);
  }
  expect_usage_error(run_isocurv({"lines", dataset("sphere"), "-o", dir / "l.svg", "--ridge-threshold", "nan"}),
                     "--ridge-threshold");
  expect_usage_error(run_isocurv({"curvature", dataset("sphere"), "--time-series", "-o", dir / "s",
                                  "--time-step", "nan"}),
                     "--time-step");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{}) << "nothing written";
}
