// The volume options reach the loaders as the README says: --spacing and --origin override every
// format's header (and info says so), an explicit option wins over a file-name token, and an
// option that cannot apply is an error naming it, never silently ignored.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv::test;
using nlohmann::json;

namespace {

/// n^3 uint8 ball (200 inside radius n/3, 10 outside), X fastest.
std::string ball_u8(int n) {
  std::string b(std::size_t(n) * n * n, char(10));
  const double c = (n - 1) / 2.0;
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x, ++i)
        if ((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c) < n * n / 9.0)
          b[i] = char(200);
  return b;
}

std::string nrrd_ball(int n) {
  const std::string size = std::to_string(n);
  return "NRRD0004\ntype: uchar\ndimension: 3\nsizes: " + size + " " + size + " " + size +
         "\nspacings: 1 1 1\nencoding: raw\n\n" + ball_u8(n);
}

/// Extent of a mesh file's vertices along each axis.
std::array<float, 3> extent(const std::string& path) {
  const auto f = isocurv::io::read_mesh(path);
  std::array<float, 3> lo, hi;
  lo.fill(std::numeric_limits<float>::max());
  hi.fill(std::numeric_limits<float>::lowest());
  for (const auto& p : f.mesh.positions)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

}  // namespace

TEST(VolumeOptions, SpacingAndOriginOverrideAHeader) {
  TempDir dir("nrrd");
  write_file(dir / "ball.nrrd", nrrd_ball(16));
  const auto r = run_isocurv({"info", dir / "ball.nrrd", "--spacing", "1", "1", "1.4", "--origin",
                              "5", "6", "7", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "info --json");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["spacing"][k].get<double>(), k == 2 ? 1.4 : 1.0, 1e-12);
    EXPECT_NEAR(j["origin"][k].get<double>(), 5.0 + k, 1e-12);
  }
  EXPECT_EQ(j["file_spacing"], json::array({1.0, 1.0, 1.0})) << "what the header said";
  EXPECT_EQ(j["file_origin"], json::array({0.0, 0.0, 0.0}));

  const auto text = run_isocurv({"info", dir / "ball.nrrd", "--spacing", "1", "1", "1.4"});
  ASSERT_TRUE(text.ok()) << text.describe();
  EXPECT_NE(text.out.find("1 1 1.4  (from --spacing; header says 1 1 1)"), std::string::npos)
      << text.out;
  const auto plain = run_isocurv({"info", dir / "ball.nrrd", "--json"});
  ASSERT_TRUE(plain.ok()) << plain.describe();
  EXPECT_FALSE(parse_json(plain.out, "info --json").contains("file_spacing"))
      << "no override, no note";

  // The mesh follows: z stretched by 1.4.
  ASSERT_TRUE(
      run_isocurv({"extract", dir / "ball.nrrd", "--iso", "100", "-o", dir / "a.ply", "--quiet"})
          .ok());
  ASSERT_TRUE(run_isocurv({"extract", dir / "ball.nrrd", "--iso", "100", "--spacing", "1", "1",
                           "1.4", "-o", dir / "b.ply", "--quiet"})
                  .ok());
  const auto a = extent(dir / "a.ply"), b = extent(dir / "b.ply");
  EXPECT_NEAR(b[0], a[0], 1e-4);
  EXPECT_NEAR(b[2], 1.4f * a[2], 1e-4);
}

TEST(VolumeOptions, SpacingOverridesAVdbTransform) {
  const auto plain = run_isocurv({"info", dataset("sphere"), "--json"});
  ASSERT_TRUE(plain.ok()) << plain.describe();
  const double s = parse_json(plain.out, "info")["spacing"][0].get<double>();
  const auto r =
      run_isocurv({"info", dataset("sphere"), "--spacing", "0.5", "0.5", "0.25", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "info --json");
  EXPECT_EQ(j["spacing"], json::array({0.5, 0.5, 0.25}));
  EXPECT_DOUBLE_EQ(j["file_spacing"][0].get<double>(), s);
}

TEST(VolumeOptions, SpacingOverridesADgtalVolHeader) {
  TempDir dir("vol");
  const int n = 8;
  std::string data(std::size_t(n) * n * n, char(0));
  data[std::size_t(4 + n * (4 + n * 4))] = char(255);
  write_file(dir / "dot.vol",
             "Center-X: 4\nCenter-Y: 4\nCenter-Z: 4\nX: 8\nY: 8\nZ: 8\nVoxel-Size: 1\n"
             "Alpha-Color: 0\nVoxel-Endian: 0\nInt-Endian: 0123\nVersion: 2\n.\n" +
                 data);
  const auto r = run_isocurv({"info", dir / "dot.vol", "--spacing", "1", "1", "1.4", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_EQ(parse_json(r.out, "info --json")["spacing"], json::array({1.0, 1.0, 1.4}));
}

// Snapping judges in index space: the same scan at another spacing snaps the same vertices (the
// lobster at 1 x 1 x 1.4 had one vertex more), so the meshes have the same triangles and their
// vertices map onto each other by the spacings.
TEST(VolumeOptions, SnappingDoesNotDependOnTheSpacing) {
  TempDir dir("snap_spacing");
  const std::string lobster = std::string(isocurv::test_paths::shared_datasets()) + "/lobster/lobster.vol";
  const std::string a = dir / "a.vtp", b = dir / "b.vtp";
  ASSERT_TRUE(run_isocurv({"extract", lobster, "--iso", "60", "-o", a, "--quiet"}, 120).ok());
  ASSERT_TRUE(run_isocurv({"extract", lobster, "--iso", "60", "--spacing", "0.3", "0.5", "2",
                           "-o", b, "--quiet"}, 120).ok());
  const isocurv::Mesh ma = isocurv::io::read_mesh(a).mesh, mb = isocurv::io::read_mesh(b).mesh;
  ASSERT_EQ(ma.positions.size(), mb.positions.size());
  ASSERT_EQ(ma.triangles, mb.triangles);
  const double scale[3] = {0.3, 0.5, 2};
  double worst = 0;
  for (std::size_t i = 0; i < ma.positions.size(); ++i)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::abs(double(mb.positions[i][k]) / scale[k] - ma.positions[i][k]));
  EXPECT_LT(worst, 1e-3) << "voxels";
}

TEST(VolumeOptions, ExplicitEndianWinsOverTheFileName) {
  TempDir dir("endian");
  // uint16 little-endian 4 x 2 x 2, value 1 everywhere except one voxel of 2.
  std::string bytes;
  for (int i = 0; i < 16; ++i)
    bytes += i == 5 ? std::string("\x02\x00", 2) : std::string("\x01\x00", 2);
  write_file(dir / "tiny_4x2x2_uint16le.raw", bytes);
  const auto named = run_isocurv({"info", dir / "tiny_4x2x2_uint16le.raw", "--json"});
  ASSERT_TRUE(named.ok()) << named.describe();
  EXPECT_EQ(parse_json(named.out, "info")["max"].get<double>(), 2.0);
  const auto big =
      run_isocurv({"info", dir / "tiny_4x2x2_uint16le.raw", "--endian", "big", "--json"});
  ASSERT_TRUE(big.ok()) << big.describe();
  EXPECT_EQ(parse_json(big.out, "info")["max"].get<double>(), 512.0)
      << "--endian big loses to the name's 'le'";
}

TEST(VolumeOptions, OptionsThatCannotApplyAreNamed) {
  TempDir dir("apply");
  write_file(dir / "ball.nrrd", nrrd_ball(8));
  expect_clean_failure(run_isocurv({"info", dir / "ball.nrrd", "--dims", "8", "8", "8"}), "--dims");
  expect_clean_failure(run_isocurv({"info", dir / "ball.nrrd", "--type", "uint8"}), "--type");
  expect_clean_failure(run_isocurv({"info", dir / "ball.nrrd", "--endian", "big"}), "--endian");
  expect_clean_failure(run_isocurv({"info", dir / "ball.nrrd", "--grid", "density"}), "--grid");
  expect_clean_failure(
      run_isocurv({"extract", dataset("sphere"), "--type", "float", "-o", dir / "o.vtp"}),
      "--type");
  expect_clean_failure(run_isocurv({"info", dir / "ball.nrrd", "--spacing", "1", "0", "1"}),
                       "--spacing");
  // Not a finite number: a usage error, as for every floating-point option (status 2).
  expect_usage_error(run_isocurv({"info", dir / "ball.nrrd", "--origin", "1", "inf", "1"}), "--origin");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"ball.nrrd"});
}

TEST(VolumeOptions, VolumeOptionsOnAMeshAreNamed) {
  TempDir dir("mesh");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "s.ply", "--quiet"}).ok());
  expect_clean_failure(
      run_isocurv({"curvature", dir / "s.ply", "--spacing", "1", "1", "2", "-o", dir / "c.vtp"}),
      "--spacing");
  expect_clean_failure(run_isocurv({"check", dir / "s.ply", "--iso", "0.5"}), "--iso");
  expect_clean_failure(run_isocurv({"render", dir / "s.ply", "--cap", "-o", dir / "s.png"}),
                       "--cap");
  expect_clean_failure(run_isocurv({"check", dir / "s.ply", "--inside", "below"}), "--inside");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"s.ply"});
}
