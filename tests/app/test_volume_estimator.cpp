// --estimator volume and --scale on the command line (issue 13): the estimator and its scale in
// --json and the VTP's field data, the Unreliable array, tighter statistics than the mesh
// estimator on a noisy CT-like ball, several scales (--scale 1,2.5: arrays suffixed _s<S>), and
// the usage errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv::test;
using nlohmann::json;

namespace {

// A CT-like ball (radius R voxels, edge blurred over a voxel, grey levels 20 and 220, uniform
// noise of +-5 grey levels, uint8) as a raw file named with its dimensions and type.
std::string write_noisy_ball(const TempDir& dir, int n, double R) {
  return write_ct_ball(dir.path(), n, R, 10, 777, 0.3, "nball_");
}

TEST(VolumeEstimatorCli, JsonFieldDataAndTighterStatistics) {
  TempDir dir("volume_estimator");
  const double R = 12;
  const std::string ball = write_noisy_ball(dir, 34, R);
  const std::string vtp = dir / "ball.vtp";
  const auto v = run_isocurv(
      {"curvature", ball, "--iso", "120.5", "-o", vtp, "--estimator", "volume", "--json"}, 120);
  ASSERT_TRUE(v.ok()) << v.describe();
  const json s = parse_json(v.out, "curvature --json");
  ASSERT_TRUE(s.contains("estimator")) << s.dump(2);
  const json& e = s["estimator"];
  EXPECT_EQ(e.value("name", ""), "volume");
  EXPECT_EQ(e.value("scale_chosen", ""), "auto");
  EXPECT_GT(e["scale_voxels"].get<double>(), 1.0) << "noisy 8-bit data: more than a voxel";
  EXPECT_NEAR(e["measured_noise"].get<double>(), 10 / std::sqrt(12.0), 1.0) << e.dump(2);
  EXPECT_EQ(e["unreliable_vertices"].get<int>(), 0) << e.dump(2);
  EXPECT_EQ(s.value("normals", ""), "volume estimator");
  // Where the estimator's time went, step by step, within the curvature stage's time.
  ASSERT_TRUE(e.contains("steps_ms")) << e.dump(2);
  double steps = 0;
  for (const char* step : {"auto_scale", "plan", "gather", "passes", "vertices", "host"}) {
    ASSERT_TRUE(e["steps_ms"].contains(step)) << step << e.dump(2);
    EXPECT_GE(e["steps_ms"][step].get<double>(), 0.0) << step;
    steps += e["steps_ms"][step].get<double>();
  }
  EXPECT_LE(steps, s["timings_ms"]["curvature"].get<double>() * 1.01 + 0.1) << s.dump(2);
  // The per-vertex scales' range, which titles quote: the Scale array's 5th and 95th percentiles.
  ASSERT_TRUE(e.contains("scale_p5") && e.contains("scale_p95")) << e.dump(2);
  EXPECT_DOUBLE_EQ(e["scale_p5"].get<double>(), e["scale_per_vertex"]["p5"].get<double>());
  EXPECT_DOUBLE_EQ(e["scale_p95"].get<double>(), e["scale_per_vertex"]["p95"].get<double>());
  EXPECT_LE(e["scale_p5"].get<double>(), e["scale_p95"].get<double>());

  const auto m =
      run_isocurv({"curvature", ball, "--iso", "120.5", "-o", dir / "mesh.vtp", "--estimator",
                   "rusinkiewicz", "--json"},
                  120);
  ASSERT_TRUE(m.ok()) << m.describe();
  const json sm = parse_json(m.out, "curvature --json");
  EXPECT_EQ(sm["estimator"].value("name", ""), "rusinkiewicz");
  // The middle 90% of H: far narrower from the volume than from the mesh on noisy data.
  auto spread = [](const json& j) {
    return j["curvature"]["H"]["p95"].get<double>() - j["curvature"]["H"]["p5"].get<double>();
  };
  EXPECT_LT(spread(s), 0.5 * spread(sm)) << s["curvature"].dump(2) << sm["curvature"].dump(2);
  EXPECT_NEAR(s["curvature"]["H"]["p50"].get<double>(), 1 / R, 0.08 / R);

  // The VTP carries the estimator and its scale as field data, and the Unreliable array.
  const std::string text = read_file(vtp);
  EXPECT_NE(text.find("Name=\"estimator\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"scale\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"Unreliable\""), std::string::npos);

  // A given scale is reported as given.
  const auto g = run_isocurv({"curvature", ball, "--iso", "120.5", "-o", dir / "g.vtp",
                              "--estimator", "volume", "--scale", "1.5", "--json"},
                             120);
  ASSERT_TRUE(g.ok()) << g.describe();
  const json sg = parse_json(g.out, "curvature --json");
  EXPECT_EQ(sg["estimator"].value("scale_chosen", ""), "given");
  EXPECT_DOUBLE_EQ(sg["estimator"]["scale"].get<double>(), 1.5);
}

const std::vector<float>* extra(const isocurv::io::MeshFile& m, const std::string& name) {
  if (!m.field) return nullptr;
  for (const auto& e : m.field->extra)
    if (e.name == name) return &e.values;
  return nullptr;
}

double median(std::vector<float> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The spread of the middle 90% of an array.
double middle_spread(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() * 95 / 100] - v[v.size() * 5 / 100];
}

TEST(VolumeEstimatorCli, SeveralScalesGiveSuffixedArraysPerScale) {
  TempDir dir("volume_estimator_scales");
  const double R = 12;
  const std::string ball = write_noisy_ball(dir, 34, R);
  const std::string vtp = dir / "ball.vtp";
  const auto r = run_isocurv({"curvature", ball, "--iso", "120.5", "-o", vtp, "--estimator",
                              "volume", "--scale", "1,2.5", "--json"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json s = parse_json(r.out, "curvature --json");
  EXPECT_EQ(s["estimator"]["scales"], json::array({"1", "2.5"})) << s["estimator"].dump(2);
  EXPECT_DOUBLE_EQ(s["estimator"]["scale"].get<double>(), 1.0) << "the first scale is the main one";
  const isocurv::io::MeshFile m = isocurv::io::read_mesh(vtp);
  ASSERT_TRUE(m.field);
  for (const char* a : {"k1", "k2", "H", "K", "ShapeIndex", "Curvedness"})
    for (const char* sc : {"_s1", "_s2.5"})
      ASSERT_NE(extra(m, std::string(a) + sc), nullptr) << a << sc;
  // The unsuffixed arrays are the first scale's.
  EXPECT_EQ(*extra(m, "H_s1"), m.field->H);
  // Both scales measure the ball's curvature; the larger one averages more noise away.
  const auto& h1 = *extra(m, "H_s1");
  const auto& h25 = *extra(m, "H_s2.5");
  EXPECT_NEAR(median(h1), 1 / R, 0.1 / R);
  EXPECT_NEAR(median(h25), 1 / R, 0.1 / R);
  EXPECT_LT(middle_spread(h25), 0.7 * middle_spread(h1));
  // Each scale equals a run at that scale alone.
  const auto one = run_isocurv({"curvature", ball, "--iso", "120.5", "-o", dir / "one.vtp",
                                "--estimator", "volume", "--scale", "2.5"},
                               120);
  ASSERT_TRUE(one.ok()) << one.describe();
  EXPECT_EQ(isocurv::io::read_mesh(dir / "one.vtp").field->H, h25);
}

TEST(VolumeEstimatorCli, UsageErrors) {
  TempDir dir("volume_estimator_errors");
  const std::string ball = write_noisy_ball(dir, 20, 6);
  struct Bad {
    std::vector<std::string> args;
    int code;
    const char* says;
  };
  const std::string out = dir / "x.vtp";
  const Bad bad[] = {
      {{"curvature", ball, "-o", out, "--estimator", "nope"}, 2, "--estimator"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "-1"}, 2, "--scale"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "nan"}, 2, "--scale"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "1,auto"}, 2, "auto"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "1,2,1"}, 2, "twice"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "1,"}, 2, "--scale"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--scale", "1e6"},
       1,
       "larger than the volume"},
      {{"curvature", ball, "-o", out, "--estimator", "rusinkiewicz", "--scale", "2"},
       1,
       "--estimator volume"},
      {{"curvature", ball, "-o", out, "--estimator", "volume", "--normals", "mesh"},
       1,
       "--normals"},
  };
  for (const Bad& b : bad) {
    const auto r = run_isocurv(b.args);
    EXPECT_EQ(r.exit_code, b.code) << r.describe();
    ASSERT_EQ(r.err_lines().size(), 1u) << r.describe();
    EXPECT_EQ(r.err_lines()[0].rfind("isocurv: ", 0), 0u) << r.describe();
    EXPECT_NE(r.err.find(b.says), std::string::npos) << r.describe();
    EXPECT_FALSE(fs::exists(out)) << r.describe();
  }
  // A mesh file cannot give the volume estimator its volume.
  ASSERT_TRUE(run_isocurv({"extract", ball, "-o", dir / "m.vtp"}).ok());
  const auto r = run_isocurv({"curvature", dir / "m.vtp", "-o", out, "--estimator", "volume"});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("needs a volume"), std::string::npos) << r.describe();
}

}  // namespace
