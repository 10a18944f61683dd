// isocurv info, devices, --help and --version, run as a subprocess.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "cli.h"

using namespace isocurv::test;
using nlohmann::json;

namespace {

/// A 24^3 float volume: 100 inside a ball of radius 8 voxels around the centre, 0 outside, with a
/// linear ramp so values are not all equal.
std::string ball_floats(int n, float* lo = nullptr, float* hi = nullptr) {
  std::string bytes(std::size_t(n) * n * n * sizeof(float), '\0');
  float* v = reinterpret_cast<float*>(bytes.data());
  float mn = 1e30f, mx = -1e30f;
  const float c = (n - 1) / 2.0f;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const float r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
        const float value = 100.0f - 10.0f * r;  // 20 at r = 8
        *v++ = value;
        mn = std::min(mn, value);
        mx = std::max(mx, value);
      }
  if (lo) *lo = mn;
  if (hi) *hi = mx;
  return bytes;
}

}  // namespace

TEST(CliInfo, TextDescribesABundledVdb) {
  const auto r = run_isocurv({"info", dataset("sphere")});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.out.find("vdb"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("level set"), std::string::npos) << "the sphere is a level set\n" << r.out;
  EXPECT_TRUE(r.err.empty()) << r.describe();
}

TEST(CliInfo, JsonOfABundledVdb) {
  const auto r = run_isocurv({"info", dataset("torus"), "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "info --json");
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.value("format", ""), "vdb");
  EXPECT_EQ(j.value("inside", ""), "above") << "the torus field is positive inside";
  ASSERT_TRUE(j["dims"].is_array());
  ASSERT_EQ(j["dims"].size(), 3u);
  EXPECT_GE(j["dims"][0].get<int>(), 60);  // 64 voxels along the longest side
  EXPECT_LT(j["min"].get<double>(), 0.0);
  EXPECT_GT(j["max"].get<double>(), 0.0);
  EXPECT_GE(j["suggested_isovalue"].get<double>(), j["min"].get<double>());
  EXPECT_LE(j["suggested_isovalue"].get<double>(), j["max"].get<double>());
  EXPECT_EQ(j["nan_count"].get<int>(), 0);
}

TEST(CliInfo, RawWithDimsTypeAndSpacing) {
  TempDir dir("raw");
  // uint16, 20 x 12 x 8 (X fastest), value = x + 100 * z.
  const int nx = 20, ny = 12, nz = 8;
  std::string bytes;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const std::uint16_t v = static_cast<std::uint16_t>(x + 100 * z);
        bytes.push_back(static_cast<char>(v & 0xff));
        bytes.push_back(static_cast<char>(v >> 8));
      }
  write_file(dir / "block.raw", bytes);
  const auto r = run_isocurv({"info", dir / "block.raw", "--dims", "20", "12", "8", "--type", "uint16", "--spacing",
                              "0.5", "0.5", "2", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "info --json");
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j["dims"], json::array({20, 12, 8}));
  EXPECT_EQ(j.value("voxel_type", ""), "uint16");
  EXPECT_DOUBLE_EQ(j["min"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["max"].get<double>(), 19.0 + 700.0);
  ASSERT_EQ(j["spacing"].size(), 3u);
  EXPECT_DOUBLE_EQ(j["spacing"][0].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["spacing"][2].get<double>(), 2.0);

  // Big-endian: the same bytes read the other way round give other values.
  const auto big = run_isocurv({"info", dir / "block.raw", "--dims", "20", "12", "8", "--type", "uint16", "--endian",
                                "big", "--json"});
  ASSERT_TRUE(big.ok()) << big.describe();
  const json jb = parse_json(big.out, "info --json");
  std::uint16_t swapped_max = 0;
  for (int z = 0; z < nz; ++z)
    for (int x = 0; x < nx; ++x) {
      const unsigned v = unsigned(x + 100 * z);
      swapped_max = std::max<std::uint16_t>(swapped_max, static_cast<std::uint16_t>(((v & 0xffu) << 8) | (v >> 8)));
    }
  EXPECT_DOUBLE_EQ(jb["max"].get<double>(), double(swapped_max)) << "--endian big reads byte-swapped values";
}

TEST(CliInfo, NrrdHeaderAndNanVoxels) {
  TempDir dir("nrrd");
  float lo = 0, hi = 0;
  std::string data = ball_floats(24, &lo, &hi);
  const float nan = std::nanf("");
  std::memcpy(data.data(), &nan, sizeof nan);  // one NaN voxel in a corner
  const std::string header =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 24 24 24\nspacings: 0.25 0.25 0.25\nencoding: raw\n"
      "endian: little\n\n";
  write_file(dir / "ball.nrrd", header + data);
  const auto r = run_isocurv({"info", dir / "ball.nrrd", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "info --json");
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.value("format", ""), "nrrd");
  EXPECT_EQ(j["dims"], json::array({24, 24, 24}));
  EXPECT_DOUBLE_EQ(j["spacing"][1].get<double>(), 0.25);
  EXPECT_EQ(j["nan_count"].get<int>(), 1) << "a NaN voxel is counted, not propagated";
  EXPECT_TRUE(std::isfinite(j["min"].get<double>()));
  EXPECT_NEAR(j["max"].get<double>(), hi, 1e-4);
}

TEST(CliDevices, TextAndJson) {
  const auto text = run_isocurv({"devices"});
  ASSERT_TRUE(text.ok()) << text.describe();
  EXPECT_NE(text.out.find("* 0"), std::string::npos) << "the default device is starred\n" << text.out;

  const auto r = run_isocurv({"devices", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "devices --json");
  ASSERT_TRUE(j.is_array());
  ASSERT_FALSE(j.empty());
  int defaults = 0;
  for (std::size_t i = 0; i < j.size(); ++i) {
    EXPECT_EQ(j[i]["index"].get<int>(), int(i));
    EXPECT_FALSE(j[i]["name"].get<std::string>().empty());
    EXPECT_GT(j[i]["compute_units"].get<int>(), 0);
    if (j[i]["default"].get<bool>()) ++defaults;
  }
  EXPECT_EQ(defaults, 1);
}

TEST(CliHelp, EveryCommandShowsAnExample) {
  for (const char* cmd : {"info", "extract", "curvature", "run", "render", "view", "check", "devices"}) {
    const auto r = run_isocurv({cmd, "--help"}, 20);
    EXPECT_EQ(r.exit_code, 0) << r.describe();
    EXPECT_NE(r.out.find(std::string("Example: isocurv ") + cmd), std::string::npos) << cmd << "\n" << r.out;
    EXPECT_NE(r.out.find("--help"), std::string::npos) << r.out;
  }
  const auto top = run_isocurv({"--help"}, 20);
  EXPECT_EQ(top.exit_code, 0) << top.describe();
  for (const char* cmd : {"info", "extract", "curvature", "run", "render", "view", "check", "devices"})
    EXPECT_NE(top.out.find(cmd), std::string::npos) << cmd << " missing from isocurv --help";
}

// The explorer's scripted mode is a user's option (demos, headless pictures), not a hidden one.
TEST(CliHelp, ViewOffersItsScriptedMode) {
  const auto r = run_isocurv({"view", "--help"}, 20);
  EXPECT_EQ(r.exit_code, 0) << r.describe();
  EXPECT_NE(r.out.find("--script"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("headless"), std::string::npos) << r.out;
}

TEST(CliHelp, UsageNamesTheProgramNotItsPath) {
  // The tests start the executable by its full path; the usage line still says "isocurv".
  const auto top = run_isocurv({"--help"}, 20);
  EXPECT_NE(top.out.find("Usage: isocurv [OPTIONS]"), std::string::npos) << top.out;
  for (const char* cmd : {"extract", "render", "lines"}) {
    const auto r = run_isocurv({cmd, "--help"}, 20);
    EXPECT_NE(r.out.find(std::string("Usage: isocurv ") + cmd + " "), std::string::npos) << r.out;
  }
  // render's examples run from a checkout on the bundled datasets.
  const auto render = run_isocurv({"render", "--help"}, 20);
  EXPECT_NE(render.out.find("isocurv render build/datasets/torus.vdb"), std::string::npos) << render.out;
  EXPECT_NE(render.out.find("../shared/datasets/vg_bunny/bunny-128.vol"), std::string::npos) << render.out;
}

TEST(CliHelp, ConventionsAreDocumented) {
  // DESIGN.md: "Say so in --help": normals point out of the object.
  const auto r = run_isocurv({"curvature", "--help"}, 20);
  EXPECT_NE(r.out.find("out of the object"), std::string::npos) << r.out;
  const auto e = run_isocurv({"extract", "--help"}, 20);
  EXPECT_NE(e.out.find("--inside"), std::string::npos) << e.out;
}

TEST(CliHelp, VersionAndNoCommand) {
  const auto v = run_isocurv({"--version"}, 20);
  EXPECT_EQ(v.exit_code, 0) << v.describe();
  EXPECT_NE(v.out.find("isocurv 0.1"), std::string::npos) << v.describe();
  const auto none = run_isocurv({}, 20);
  EXPECT_NE(none.exit_code, 0) << "a subcommand is required\n" << none.describe();
  EXPECT_EQ(none.signal, 0);
}
