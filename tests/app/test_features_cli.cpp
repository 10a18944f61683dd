// isocurv features end to end: arrays written and read back, radii in % of the diagonal, suffixes
// for several radii, and one-line errors for bad radii and for Vr without a volume.
#include <gtest/gtest.h>

#include <cmath>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

const std::vector<float>* extra(const io::MeshFile& m, const std::string& name) {
  if (!m.field) return nullptr;
  for (const auto& e : m.field->extra)
    if (e.name == name) return &e.values;
  return nullptr;
}

TEST(CliFeatures, SphereArraysAndSeveralRadii) {
  TempDir dir("features");
  const auto r = run_isocurv({"features", dataset("sphere"), "--radius", "10%,0.3", "-o", dir / "s.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "features --json");
  EXPECT_EQ(j["features"]["radii"][1]["world"].get<double>(), 0.3);
  EXPECT_EQ(j["features"]["mean_curvature_from"], "volume integral invariant");
  ASSERT_TRUE(j["timings_ms"].contains("features"));
  const io::MeshFile m = io::read_mesh(dir / "s.vtp");
  for (const char* name : {"LBE_r10%", "NSV_r10%", "Vr_r10%", "H_ii_r10%", "K_ii_r10%", "SI_ii_r10%", "H_ii_r0.3",
                           "FeatureBoundary"})
    ASSERT_NE(extra(m, name), nullptr) << name;
  ASSERT_FALSE(m.field->H.empty()) << "the curvature arrays are written too";
  // The bundled sphere has R = 0.8: H_ii = 1.25 away from the flagged vertices.
  const auto& h = *extra(m, "H_ii_r0.3");
  const auto& flag = *extra(m, "FeatureBoundary");
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < h.size(); ++v)
    if (flag[v] == 0) sum += h[v], ++count;
  ASSERT_GT(count, h.size() / 2);
  EXPECT_NEAR(sum / double(count), 1.25, 0.02);
}

// One radius: the arrays carry no suffix, so the file says the radius and a picture's title
// quotes it; with several, each array's own suffix does.
TEST(CliFeatures, APictureOfOneRadiusSaysTheRadius) {
  TempDir dir("features_title");
  ASSERT_TRUE(run_isocurv({"features", dataset("torus"), "--radius", "3%", "--features", "H_ii,SI_ii",
                           "-o", dir / "t.vtp", "--quiet"})
                  .ok());
  const auto r = run_isocurv({"render", dir / "t.vtp", "--color", "SI_ii", "-o", dir / "t.png", "--json", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "render --json");
  EXPECT_NE(j.value("title", "").find("r = 3%"), std::string::npos) << j.dump(2);
  const auto h = run_isocurv({"render", dir / "t.vtp", "--color", "H", "-o", dir / "h.png", "--json", "--quiet"});
  ASSERT_TRUE(h.ok()) << h.describe();
  EXPECT_EQ(parse_json(h.out, "render --json").value("title", "").find("r = "), std::string::npos)
      << "not a feature array: no radius";
}

TEST(CliFeatures, MeshInputAndBadRadii) {
  TempDir dir("features_bad");
  ASSERT_TRUE(run_isocurv({"curvature", dataset("sphere"), "-o", dir / "s.vtp", "--quiet"}).ok());
  const auto mesh = run_isocurv({"features", dir / "s.vtp", "--radius", "0.2", "-o", dir / "f.ply", "--json"});
  ASSERT_TRUE(mesh.ok()) << mesh.describe();
  EXPECT_EQ(parse_json(mesh.out, "features --json")["features"]["mean_curvature_from"], "surface samples");
  expect_clean_failure(run_isocurv({"features", dir / "s.vtp", "--radius", "0.2", "--features", "Vr", "-o",
                                    dir / "v.vtp"}),
                       "Vr");
  expect_clean_failure(run_isocurv({"features", dataset("sphere"), "--radius", "-1", "-o", dir / "n.vtp"}),
                       "--radius");
  expect_clean_failure(run_isocurv({"features", dataset("sphere"), "--radius", "50", "-o", dir / "n.vtp"}),
                       "larger than the surface");
  expect_clean_failure(run_isocurv({"features", dataset("sphere"), "--radius", "0.2", "--features", "LBE,foo", "-o",
                                    dir / "n.vtp"}),
                       "foo");
  EXPECT_FALSE(fs::exists(dir / "v.vtp"));
  EXPECT_FALSE(fs::exists(dir / "n.vtp"));
}

TEST(CliFeatures, AMeshFileKeepsItsEarlierArraysWhenCurvatureIsEstimatedAgain) {
  // A .ply carries the arrays but not Area, so features estimates the curvature again: the
  // file's arrays from the earlier run (other radii) must stay.
  TempDir dir("features_keep");
  ASSERT_TRUE(run_isocurv({"features", dataset("sphere"), "--radius", "0.2,0.3", "--features", "LBE,H_ii",
                           "-o", dir / "f.ply", "--quiet"})
                  .ok());
  const auto again = run_isocurv({"features", dir / "f.ply", "--radius", "0.25", "--features", "LBE", "-o",
                                  dir / "g.vtp", "--quiet"});
  ASSERT_TRUE(again.ok()) << again.describe();
  const io::MeshFile m = io::read_mesh(dir / "g.vtp");
  for (const char* name : {"LBE", "LBE_r0.2", "H_ii_r0.3", "FeatureBoundary"}) EXPECT_NE(extra(m, name), nullptr) << name;
  ASSERT_FALSE(m.field->H.empty());
  // A .vtp carries a complete field, which --flip makes stale: estimated again, the arrays stay.
  ASSERT_TRUE(run_isocurv({"features", dataset("sphere"), "--radius", "0.3", "--features", "H_ii",
                           "-o", dir / "f.vtp", "--quiet"})
                  .ok());
  const auto flipped = run_isocurv({"features", dir / "f.vtp", "--flip", "--radius", "0.25",
                                    "--features", "LBE", "-o", dir / "h.vtp", "--quiet"});
  ASSERT_TRUE(flipped.ok()) << flipped.describe();
  const io::MeshFile h = io::read_mesh(dir / "h.vtp");
  EXPECT_NE(extra(h, "H_ii"), nullptr) << "the file's array from the first run";
  EXPECT_NE(extra(h, "LBE"), nullptr);
  const io::MeshFile f = io::read_mesh(dir / "f.vtp");
  ASSERT_EQ(h.field->H.size(), f.field->H.size());
  EXPECT_LT(h.field->H[0] * f.field->H[0], 0.0f) << "flipped: H changes sign";
}

}  // namespace
