// isocurv measure end to end on the bundled analytic solids: the Minkowski functionals against
// their exact values, the Gauss-Bonnet check, the CSV, and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/app/cli.h"

namespace isocurv::test {
namespace {

using json = nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

json measure(const std::string& input, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"measure", input, "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = run_isocurv(args, 120);
  EXPECT_TRUE(r.ok()) << r.describe();
  return parse_json(r.out, "measure --json");
}

// Bounds: the marching-cubes mesh of a 64^3-ish sampling loses area and volume at second order
// (about 0.1% here), the volume estimator's H is within 1% on these smooth solids
// (docs/curvature.md), and the estimated K integrates to 2 pi chi within 1%.
TEST(CliMeasure, SphereAndTorusAgainstTheirExactMeasures) {
  const json s = measure(dataset("sphere"));
  ASSERT_EQ(s["objects"].size(), 1u) << s.dump();
  const json& b = s["objects"][0];
  const double R = 0.8;
  EXPECT_EQ(s["estimator"], "volume");
  // The scale the measure belongs to, as titles word it, and both areas.
  EXPECT_EQ(s.value("curvature", "").rfind("volume, scale ", 0), 0u) << s.dump();
  EXPECT_TRUE(b["resolved"].get<bool>()) << b.dump();
  EXPECT_GT(b["scale"].get<double>(), 0.0);
  EXPECT_NEAR(b["mesh_area"].get<double>(), b["area"].get<double>(), 0.01 * b["area"].get<double>());
  EXPECT_TRUE(b["closed"].get<bool>());
  EXPECT_EQ(b["euler_characteristic"], 2);
  EXPECT_EQ(b["genus"], 0);
  EXPECT_NEAR(b["area"].get<double>(), 4 * kPi * R * R, 0.005 * 4 * kPi * R * R);
  EXPECT_NEAR(b["volume"].get<double>(), 4 * kPi * R * R * R / 3, 0.005 * 4 * kPi * R * R * R / 3);
  EXPECT_NEAR(b["integral_H"].get<double>(), 4 * kPi * R, 0.01 * 4 * kPi * R);
  EXPECT_LT(std::abs(b["gauss_bonnet_gap"].get<double>()), 0.01);

  const json t = measure(dataset("torus"));
  ASSERT_EQ(t["objects"].size(), 1u) << t.dump();
  const json& o = t["objects"][0];
  const double Rm = 0.6, r = 0.25;  // datasets/fields.cpp
  EXPECT_EQ(o["euler_characteristic"], 0);
  EXPECT_EQ(o["genus"], 1);
  EXPECT_NEAR(o["area"].get<double>(), 4 * kPi * kPi * Rm * r, 0.005 * 4 * kPi * kPi * Rm * r);
  EXPECT_NEAR(o["volume"].get<double>(), 2 * kPi * kPi * Rm * r * r, 0.005 * 2 * kPi * kPi * Rm * r * r);
  EXPECT_NEAR(o["integral_H"].get<double>(), 2 * kPi * kPi * Rm, 0.01 * 2 * kPi * kPi * Rm);
  // chi = 0: the gap is the integral of K over 2 pi, which should vanish.
  EXPECT_LT(std::abs(o["integral_K"].get<double>()), 0.01 * 2 * kPi);
  // Its one handle is on the smooth surface: the curvature's integral counts it.
  EXPECT_NEAR(o["curvature_genus"].get<double>(), 1.0, 0.01);
  EXPECT_FALSE(o["fine_handles"].get<bool>());
}

// A CT's noise tunnels: the lobster's body at its suggested isovalue has hundreds of handles
// narrower than a voxel or two, which the smoothed surface the curvature describes does not
// have. The measure says so (fine_handles, and a line of text) instead of leaving a +76% gap
// unexplained, and counts the handles the curvature sees.
TEST(CliMeasure, NoiseTunnelsAreNamedAsHandlesFinerThanTheScale) {
  const std::string lobster = std::string(test_paths::shared_datasets()) + "/lobster/lobster.vol";
  if (!std::filesystem::exists(lobster)) GTEST_SKIP() << "no " << lobster;
  const json m = measure(lobster);
  const json& body = m["objects"][0];
  ASSERT_TRUE(body["resolved"].get<bool>()) << body.dump();
  const double genus = body["genus"].get<double>(), seen = body["curvature_genus"].get<double>();
  EXPECT_GT(genus, 100.0) << body.dump();
  EXPECT_GT(seen, 0.0);
  EXPECT_LT(seen, 0.5 * genus);
  EXPECT_TRUE(body["fine_handles"].get<bool>());
  const auto text = run_isocurv({"measure", lobster, "--rows", "1"}, 120);
  ASSERT_TRUE(text.ok()) << text.describe();
  EXPECT_NE(text.out.find("handles finer than the curvature scale (object 1"), std::string::npos)
      << text.out;
}

// The Gauss-Bonnet gap measures the curvature, not the integration: Meyer's K (angle defects over
// mixed areas) keeps Gauss-Bonnet with its own Area to rounding, and so must the measure, also
// where its normals make the patches curved (which once moved the sphere's gap off zero).
TEST(CliMeasure, AGaussBonnetKeepingEstimatorHasNoGap) {
  for (const char* name : {"sphere", "torus"}) {
    const json m = measure(dataset(name), {"--estimator", "meyer"});
    ASSERT_EQ(m["objects"].size(), 1u) << m.dump();
    const json& o = m["objects"][0];
    EXPECT_EQ(m["curvature"], "meyer");
    EXPECT_LT(std::abs(o["gauss_bonnet_gap"].get<double>()), 1e-6) << name << o.dump();
  }
}

TEST(CliMeasure, CsvHasARowPerComponentAndATotalAndBadOutputsAreRefused) {
  TempDir dir("measure");
  const auto r = run_isocurv({"measure", dataset("torus"), "--csv", dir / "t.csv"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.out.find("total"), std::string::npos) << r.out;
  const std::string csv = read_file(dir / "t.csv");
  EXPECT_EQ(csv.rfind("object,vertices,triangles,closed,area,volume,integral_H", 0), 0u) << csv;
  EXPECT_NE(csv.find("\n1,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\ntotal,"), std::string::npos) << csv;
  expect_clean_failure(run_isocurv({"measure", dataset("torus"), "--csv", dir / "no/such/dir/t.csv"}),
                       "t.csv");
  expect_clean_failure(run_isocurv({"measure", dir / "missing.vdb"}), "missing.vdb");
}

}  // namespace
}  // namespace isocurv::test
