// The empty surface, one rule (README, "The empty surface"): extract warns and writes the empty
// mesh; curvature, run, render and check refuse it with one line giving the value range; an
// isovalue at the end of the range, where the tie rule leaves no voxel inside, says why.
#include <gtest/gtest.h>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv::test;

namespace {

/// An 8 x 8 x 1 uint8 slice (values 0..63): a value range, but no cell, hence no surface at any
/// isovalue.
std::string write_slice(const TempDir& dir) {
  std::string bytes;
  for (int i = 0; i < 64; ++i) bytes.push_back(char(i));
  const std::string path = dir / "slice_8x8x1_uint8.raw";
  write_file(path, bytes);
  return path;
}

}  // namespace

TEST(EmptySurface, ExtractWarnsAndWritesTheEmptyMesh) {
  TempDir dir("extract");
  const std::string slice = write_slice(dir);
  for (const char* ext : {".vtp", ".ply"}) {
    const std::string out = dir / (std::string("empty") + ext);
    const auto r = run_isocurv({"extract", slice, "--iso", "10", "-o", out});
    EXPECT_EQ(r.exit_code, 0) << r.describe();
    const auto lines = r.err_lines();
    ASSERT_EQ(lines.size(), 1u) << r.describe();
    EXPECT_EQ(lines[0].rfind("isocurv: warning:", 0), 0u) << r.describe();
    EXPECT_NE(lines[0].find("gives no surface"), std::string::npos) << r.describe();
    EXPECT_NE(lines[0].find("[0, 63]"), std::string::npos) << "gives the value range\n"
                                                           << r.describe();
    ASSERT_TRUE(fs::exists(out)) << ext;
    EXPECT_TRUE(isocurv::io::read_mesh(out).mesh.triangles.empty()) << ext;
  }
  const auto quiet = run_isocurv({"extract", slice, "--iso", "10", "-o", dir / "q.ply", "--quiet"});
  EXPECT_EQ(quiet.exit_code, 0) << quiet.describe();
  EXPECT_TRUE(quiet.err.empty()) << quiet.describe();
}

TEST(EmptySurface, CommandsThatNeedTrianglesRefuseIt) {
  TempDir dir("refuse");
  const std::string slice = write_slice(dir);
  expect_clean_failure(run_isocurv({"curvature", slice, "--iso", "10", "-o", dir / "c.vtp"}),
                       "gives no surface");
  expect_clean_failure(run_isocurv({"run", slice, "--iso", "10", "-o", dir / "out"}),
                       "gives no surface");
  expect_clean_failure(run_isocurv({"render", slice, "--iso", "10", "-o", dir / "r.png"}),
                       "gives no surface");
  const auto check = run_isocurv({"check", slice, "--iso", "10", "--json"});
  expect_clean_failure(check, "gives no surface");
  EXPECT_NE(check.err.find("[0, 63]"), std::string::npos) << check.describe();
  EXPECT_TRUE(check.out.empty()) << check.describe();
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"slice_8x8x1_uint8.raw"});
}

TEST(EmptySurface, IsovalueAtTheMaximumSaysWhy) {
  TempDir dir("max");
  const auto info = run_isocurv({"info", dataset("torus"), "--json"});
  ASSERT_TRUE(info.ok()) << info.describe();
  char max[64];
  std::snprintf(max, sizeof max, "%.9g", parse_json(info.out, "info --json")["max"].get<double>());
  for (const char* cmd : {"extract", "curvature", "render"}) {
    const auto r = run_isocurv({cmd, dataset("torus"), "--iso", max, "-o", dir / "o.ply"});
    expect_clean_failure(r, "equals the maximum");
    EXPECT_NE(r.err.find("counts as outside"), std::string::npos) << r.describe();
  }
  expect_clean_failure(run_isocurv({"check", dataset("torus"), "--iso", max}),
                       "equals the maximum");
  // A level set's object is below the isovalue: there the minimum is the end with nothing inside.
  const auto sphere = run_isocurv({"info", dataset("sphere"), "--json"});
  ASSERT_TRUE(sphere.ok()) << sphere.describe();
  char min[64];
  std::snprintf(min, sizeof min, "%.9g",
                parse_json(sphere.out, "info --json")["min"].get<double>());
  expect_clean_failure(
      run_isocurv({"extract", dataset("sphere"), "--iso", min, "-o", dir / "o.ply"}),
      "equals the minimum");
  EXPECT_TRUE(dir.entries().empty()) << ::testing::PrintToString(dir.entries());
}
