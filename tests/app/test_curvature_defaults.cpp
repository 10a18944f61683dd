// Curvature defaults on volumes: the volume estimator by default (issue 37); for the mesh
// estimators volume normals by default, face normals where the gradient misleads (counted in the
// JSON); area-weighted statistics without the unreliable vertices.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "cli.h"

using namespace isocurv::test;
using nlohmann::json;

namespace {

}  // namespace

TEST(CurvatureDefaults, CtLikeVolumeGivesPlausibleStatistics) {
  TempDir dir("ct_ball");
  const double R = 14;
  const std::string ball = write_ct_ball(dir.path(), 40, R, 6, 12345);
  // 120 is a voxel value (integer isovalue on integer data, as CT users choose).
  const auto r =
      run_isocurv({"run", ball, "--iso", "120", "-o", dir / "out", "--size", "160x120", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json s = parse_json(r.out, "run --json");
  EXPECT_EQ(s.value("normals", ""), "volume estimator") << "the default on volume input";
  EXPECT_EQ(s["estimator"].value("name", ""), "volume") << s.dump(2);
  EXPECT_EQ(s["estimator"].value("scale_chosen", ""), "auto") << s.dump(2);
  ASSERT_TRUE(s["estimator"].contains("scale_per_vertex")) << s.dump(2);
  const json& c = s["curvature"];
  ASSERT_TRUE(c.is_object()) << s.dump(2);
  EXPECT_NEAR(c["H"]["p50"].get<double>(), 1 / R, 0.1 / R) << c.dump(2);
  EXPECT_NEAR(c["H"]["mean"].get<double>(), 1 / R, 0.1 / R) << c.dump(2);
  EXPECT_NEAR(c["K"]["mean"].get<double>(), 1 / (R * R), 0.25 / (R * R)) << c.dump(2);
  EXPECT_GT(c["H"]["p5"].get<double>(), 0.0) << "a ball is convex everywhere: " << c.dump(2);
  EXPECT_LT(c["H"]["p95"].get<double>(), 2 / R) << c.dump(2);
  EXPECT_LT(c["unreliable_vertices"].get<double>(), 0.01 * s["vertices"].get<double>())
      << c.dump(2);
  EXPECT_EQ(c["vertices_counted"].get<std::size_t>() + c["unmeasured_vertices"].get<std::size_t>() +
                c["unreliable_vertices"].get<std::size_t>() + c["non_finite_vertices"].get<std::size_t>(),
            s["vertices"].get<std::size_t>());
  EXPECT_EQ(c.value("weights", "").rfind("Area", 0), 0u) << c.dump(2);
}

TEST(CurvatureDefaults, ThinPlateFallbacksAreCounted) {
  // A plate of 128 one voxel thick, a one-voxel gap, then a slab of 255: at isovalue 40 the
  // gradient on the plate's upper face points down (it sees the slab).
  TempDir dir("thin_plate");
  const int n = 24;
  std::string bytes(std::size_t(n) * n * n, '\0');
  for (int z = 0; z < n; ++z)
    for (int y = 4; y < 20; ++y)
      for (int x = 4; x < 20; ++x)
        bytes[(std::size_t(z) * n + y) * n + x] = z == 8                 ? char(128)
                                                  : (z >= 10 && z <= 15) ? char(255)
                                                                         : 0;
  const std::string path = dir / "plate_24x24x24_uint8.raw";
  write_file(path, bytes);
  const auto r = run_isocurv(
      {"curvature", path, "--iso", "40", "--estimator", "rusinkiewicz", "-o", dir / "p.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "curvature --json");
  EXPECT_EQ(j.value("normals", ""), "volume");
  ASSERT_TRUE(j.contains("normal_fallbacks")) << j.dump(2);
  EXPECT_GE(j["normal_fallbacks"]["opposed"].get<int>(), 16 * 16 - 4 * 16) << j.dump(2);
  EXPECT_EQ(j["normal_fallbacks"]["count"].get<int>(),
            j["normal_fallbacks"]["opposed"].get<int>() +
                j["normal_fallbacks"]["weak_gradient"].get<int>());
  // The flat tops and bottoms have no curvature, so the median |H| is small.
  EXPECT_LT(std::fabs(j["curvature"]["H"]["p50"].get<double>()), 0.05) << j.dump(2);

  // Mesh normals stay available on request, and report no fallbacks.
  const auto m = run_isocurv(
      {"curvature", path, "--iso", "40", "--normals", "mesh", "-o", dir / "m.vtp", "--json"});
  ASSERT_TRUE(m.ok()) << m.describe();
  const json mj = parse_json(m.out, "curvature --json");
  EXPECT_EQ(mj.value("normals", ""), "mesh");
  EXPECT_FALSE(mj.contains("normal_fallbacks"));
}

TEST(CurvatureDefaults, MeshInputKeepsMeshNormals) {
  TempDir dir("mesh_default");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "s.ply", "--quiet"}).ok());
  const auto r = run_isocurv({"curvature", dir / "s.ply", "-o", dir / "c.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "curvature --json");
  EXPECT_EQ(j.value("normals", ""), "mesh");
  EXPECT_FALSE(j["timings_ms"].contains("normals"));
}

TEST(CurvatureDefaults, LobsterAtAVoxelValue) {
  // The case: with mesh normals and plain statistics, iso 40 gave H min -1024, K max
  // 1,048,576 and mean K 955. Loose bounds: the mesher may change (vertex snapping).
  const std::string lobster = std::string(isocurv::test_paths::shared_datasets()) + "/lobster/lobster.vol";
  if (!fs::exists(lobster)) GTEST_SKIP() << "no " << lobster;
  TempDir dir("lobster");
  const auto r =
      run_isocurv({"curvature", lobster, "--iso", "40", "--estimator", "rusinkiewicz", "-o",
                   dir / "l.ply", "--json"},
                  300);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "curvature --json");
  EXPECT_EQ(j.value("normals", ""), "volume");
  const double vertices = j["vertices"].get<double>();
  const double fallbacks = j["normal_fallbacks"]["count"].get<double>();
  EXPECT_GT(fallbacks, 0.002 * vertices) << "thin structures: about 1% of the vertices";
  EXPECT_LT(fallbacks, 0.03 * vertices);
  const json& c = j["curvature"];
  EXPECT_LT(c["unreliable_vertices"].get<double>(), 0.03 * vertices) << c.dump(2);
  EXPECT_LT(std::fabs(c["K"]["mean"].get<double>()), 0.1) << c.dump(2);
  EXPECT_GT(c["H"]["min"].get<double>(), -10.0) << c.dump(2);
  EXPECT_LT(c["K"]["max"].get<double>(), 100.0) << c.dump(2);
}
