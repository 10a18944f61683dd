// isocurv compare end to end: every estimator on a bundled analytic dataset and on a mesh file.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "cli.h"

using namespace isocurv::test;
using nlohmann::json;

TEST(CliCompare, AnalyticDatasetJson) {
  const auto r = run_isocurv({"compare", dataset("torus"), "--json"}, 120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "compare --json");
  EXPECT_EQ(j["analytic_field"], "torus");
  EXPECT_EQ(j["normals"], "volume");
  ASSERT_EQ(j["estimators"].size(), 9u) << j.dump(2);
  std::map<std::string, json> by_name;
  for (const json& e : j["estimators"]) by_name[e["estimator"].get<std::string>()] = e;
  for (const char* n : {"rusinkiewicz", "batagelo", "prantl3", "prantl2", "quadric", "cubic",
                        "sampling", "meyer", "volume"}) {
    ASSERT_TRUE(by_name.count(n)) << n;
    EXPECT_GT(by_name[n]["counted"].get<int>(), 1000) << n;
    EXPECT_GE(by_name[n]["time_ms"].get<double>(), 0.0) << n;
  }
  // The torus's mean curvature lies in [1/(R+r) .. 1/r] / 2-ish; p50 H is positive.
  EXPECT_GT(by_name["rusinkiewicz"]["H"]["p50"].get<double>(), 0);
  const double rk = by_name["rusinkiewicz"]["exact_error"]["K_relative_rms"].get<double>();
  EXPECT_LT(rk, 0.1);
  EXPECT_LT(by_name["batagelo"]["exact_error"]["K_relative_rms"].get<double>(), rk);
  // prantl2 and prantl3 have the same H (a property of the method), so they agree closely.
  EXPECT_LT(j["agreement_H_K"]["prantl3"]["prantl2"][0].get<double>(), 1e-4);
  // The volume estimator, on the volume input, is the most accurate of them on this field.
  for (const auto& [name, e] : by_name)
    if (name != "volume") {
      EXPECT_LE(by_name["volume"]["exact_error"]["H_relative_rms"].get<double>(),
                e["exact_error"]["H_relative_rms"].get<double>())
          << name;
    }
  EXPECT_GT(j["agreement_H_K"]["rusinkiewicz"]["quadric"][0].get<double>(), 0.1);
}

TEST(CliCompare, MeshFileAndReferenceDevice) {
  TempDir dir("compare");
  const std::string mesh = dir / "torus.ply";
  ASSERT_TRUE(run_isocurv({"extract", dataset("torus"), "-o", mesh, "--quiet"}).ok());
  const auto r = run_isocurv({"compare", mesh, "--device", "reference"}, 120);
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_NE(r.out.find("mesh normals"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("batagelo      reference"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("volume "), std::string::npos) << "a mesh file has no volume: " << r.out;
  EXPECT_EQ(r.out.find("analytic field"), std::string::npos) << r.out;
  const auto bad = run_isocurv({"compare", mesh, "--iso", "3"});
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  ASSERT_EQ(bad.err_lines().size(), 1u) << bad.describe();
  EXPECT_EQ(bad.err_lines()[0].rfind("isocurv:", 0), 0u) << bad.describe();
}

// --normals area and face-average reach the mesh estimators as they do in `curvature` (they were
// named in the report but the estimators kept their own normals).
TEST(CliCompare, AreaAndFaceAverageNormalsTakeEffect) {
  TempDir dir("compare_normals");
  const std::string mesh = dir / "torus.ply";
  ASSERT_TRUE(run_isocurv({"extract", dataset("torus"), "-o", mesh, "--quiet"}).ok());
  std::map<std::string, double> p50;
  for (const char* normals : {"mesh", "area", "face-average"}) {
    const auto r = run_isocurv({"compare", mesh, "--normals", normals, "--json"}, 120);
    ASSERT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "compare --json");
    EXPECT_EQ(j["normals"], normals);
    for (const json& e : j["estimators"])
      if (e["estimator"] == "rusinkiewicz") p50[normals] = e["H"]["p50"].get<double>();
  }
  EXPECT_NE(p50["area"], p50["mesh"]);
  EXPECT_NE(p50["face-average"], p50["mesh"]);
}

TEST(CliCompare, OptionsItWouldIgnoreAreRefusedTheOthersTakeEffect) {
  // compare runs every estimator and reports no AO: --estimator and --ao-scale would change
  // nothing, so they are usage errors, before any work.
  expect_usage_error(run_isocurv({"compare", dataset("torus"), "--estimator", "volume"}), "--estimator");
  expect_usage_error(run_isocurv({"compare", dataset("torus"), "--ao-scale", "2"}), "--ao-scale");
  expect_usage_error(run_isocurv({"compare", dataset("torus"), "--scale", "1,2"}), "--scale");
  TempDir dir("compare_opts");
  const std::string mesh = dir / "torus.ply";
  ASSERT_TRUE(run_isocurv({"extract", dataset("torus"), "-o", mesh, "--quiet"}).ok());
  expect_usage_error(run_isocurv({"compare", mesh, "--scale", "2"}), "--scale");
  // --scale and --batagelo-weights reach the volume and batagelo rows: their H differs from the
  // defaults' (and nothing else does).
  auto rows = [](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"compare", dataset("torus"), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args, 120);
    EXPECT_TRUE(r.ok()) << r.describe();
    std::map<std::string, json> by_name;
    const json j = parse_json(r.out, "compare --json");
    for (const json& e : j["estimators"]) by_name[e["estimator"].get<std::string>()] = e;
    return by_name;
  };
  auto base = rows({}), scaled = rows({"--scale", "0.08", "--batagelo-weights", "inverse-square"});
  EXPECT_NE(base["volume"]["H"]["p1"], scaled["volume"]["H"]["p1"]) << "--scale did not reach the volume row";
  EXPECT_NE(base["batagelo"]["H"]["p1"], scaled["batagelo"]["H"]["p1"]) << "--batagelo-weights did not reach batagelo";
  EXPECT_EQ(base["rusinkiewicz"]["H"], scaled["rusinkiewicz"]["H"]);
}
