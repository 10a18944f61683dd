// --ao-method on the command line: the default is today's AO, every method names itself in the
// JSON, the ray casts need a volume, and the AO arrays differ where the methods do.
#include <gtest/gtest.h>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

std::vector<float> ao_of(const std::string& vtp) {
  const io::MeshFile m = io::read_mesh(vtp);
  return m.field ? std::vector<float>(m.field->ao.begin(), m.field->ao.end())
                 : std::vector<float>{};
}

TEST(CliAo, EveryMethodRunsAndNamesItself) {
  TempDir dir("ao");
  const std::string torus = dataset("torus");
  const auto base = run_isocurv({"curvature", torus, "-o", dir / "default.vtp", "--json"});
  ASSERT_TRUE(base.ok()) << base.describe();
  EXPECT_EQ(parse_json(base.out, "curvature --json")["ao"]["method"], "griffin");
  const std::vector<float> def = ao_of(dir / "default.vtp");
  ASSERT_FALSE(def.empty());
  for (const char* m :
       {"griffin", "griffin-exact", "hattori", "prantl", "raycast", "raycast-cos"}) {
    const std::string out = dir / (std::string(m) + ".vtp");
    const auto r = run_isocurv({"curvature", torus, "--ao-method", m, "-o", out, "--json"}, 120);
    ASSERT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "curvature --json");
    EXPECT_EQ(j["ao"]["method"], m);
    EXPECT_GT(j["ao"]["mean"].get<double>(), 0.3) << m;
    EXPECT_LE(j["ao"]["mean"].get<double>(), 1.0) << m;
    EXPECT_TRUE(j["timings_ms"].contains("ao") || std::string(m) == "griffin") << m;
    const std::vector<float> a = ao_of(out);
    ASSERT_EQ(a.size(), def.size()) << m;
    if (std::string(m) == "griffin")
      EXPECT_EQ(a, def) << "--ao-method griffin is the default, unchanged";
    else
      EXPECT_NE(a, def) << m;
    for (float x : a) ASSERT_TRUE(x >= 0 && x <= 1) << m;
  }
  // The ray cast on a mesh file: one clear line; --hattori-half only with hattori.
  expect_clean_failure(run_isocurv({"curvature", dir / "default.vtp", "--ao-method", "raycast",
                                    "-o", dir / "x.vtp"}),
                       "needs a volume");
  const auto mesh_ok = run_isocurv({"curvature", dir / "default.vtp", "--ao-method", "hattori",
                                    "--hattori-half", "-o", dir / "h.vtp", "--json"});
  ASSERT_TRUE(mesh_ok.ok()) << mesh_ok.describe();
  EXPECT_EQ(parse_json(mesh_ok.out, "json")["ao"]["hattori"], "half");
  expect_clean_failure(run_isocurv({"curvature", torus, "--hattori-half", "-o", dir / "y.vtp"}),
                       "--hattori-half");
  expect_usage_error(run_isocurv({"curvature", torus, "--ao-method", "guess", "-o", dir / "z.vtp"}),
                     "--ao-method");
}

TEST(CliAo, RenderAndRunTakeIt) {
  TempDir dir("ao_render");
  const auto r = run_isocurv({"render", dataset("torus"), "--ao-method", "raycast", "--color", "AO",
                              "--size", "320x240", "-o", dir / "ao.png"},
                             180);
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_EQ(png_size(dir / "ao.png")[0], 320u);
  const auto run = run_isocurv({"run", dataset("torus"), "--ao-method", "griffin-exact", "--size",
                                "320x240", "-o", dir / "out", "--json"},
                               180);
  ASSERT_TRUE(run.ok()) << run.describe();
  EXPECT_EQ(parse_json(run.out, "run --json")["ao"]["method"], "griffin-exact");
}

}  // namespace
