// --estimator with the seeds' other mesh estimators: each writes the arrays it fills and no
// others, and names itself in the JSON and the VTP.
#include <gtest/gtest.h>

#include "cli.h"
#include "io/mesh_file.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

TEST(CliEstimatorChoice, MeshEstimatorsFillWhatTheyCan) {
  TempDir dir("estimator_choice");
  struct Case {
    const char* name;
    bool directions, derivative;
  };
  for (const Case c : {Case{"batagelo", true, true}, Case{"prantl2", false, false}, Case{"meyer", false, false}}) {
    const std::string out = dir / (std::string(c.name) + ".vtp");
    const auto r = run_isocurv({"curvature", dataset("torus"), "--estimator", c.name, "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    EXPECT_EQ(parse_json(r.out, "curvature --json")["estimator"]["name"], c.name);
    const io::MeshFile m = io::read_mesh(out);
    ASSERT_TRUE(m.field);
    const std::size_t n = m.mesh.vertex_count();
    EXPECT_EQ(m.field->H.size(), n) << c.name;
    EXPECT_EQ(m.field->K.size(), n) << c.name;
    EXPECT_EQ(m.field->dir1.size(), c.directions ? n : 0u) << c.name << ": absent, never zeros";
    EXPECT_EQ(m.field->dcurv.size(), c.derivative ? n : 0u) << c.name;
    // The torus (tube 0.25): the median H over the vertices is positive and near the exact range.
    std::vector<float> h(m.field->H.begin(), m.field->H.end());
    std::nth_element(h.begin(), h.begin() + h.size() / 2, h.end());
    EXPECT_GT(h[h.size() / 2], 0.5f) << c.name;
    EXPECT_LT(h[h.size() / 2], 4.0f) << c.name;
  }
  expect_usage_error(run_isocurv({"curvature", dataset("torus"), "--estimator", "guess", "-o", dir / "x.vtp"}),
                     "--estimator");
  // Every normal source reaches every mesh estimator: the normals written are the ones asked for.
  std::vector<std::vector<Vec3f>> normals;
  for (const char* source : {"mesh", "area", "face-average", "volume"}) {
    const std::string out = dir / (std::string("n_") + source + ".vtp");
    const auto r = run_isocurv({"curvature", dataset("torus"), "--estimator", "batagelo", "--normals", source, "-o",
                                out, "--quiet"});
    ASSERT_TRUE(r.ok()) << r.describe();
    normals.push_back(io::read_mesh(out).field->normals);
  }
  for (std::size_t i = 1; i < normals.size(); ++i) EXPECT_NE(normals[i], normals[0]) << "source " << i;
}

TEST(CliEstimatorChoice, BatageloNeighbourWeights) {
  TempDir dir("batagelo_weights");
  std::vector<float> k[2];
  int i = 0;
  for (const char* w : {"uniform", "inverse-square"}) {
    const std::string out = dir / (std::string(w) + ".vtp");
    const auto r = run_isocurv(
        {"curvature", dataset("torus"), "--estimator", "batagelo", "--batagelo-weights", w, "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    EXPECT_EQ(parse_json(r.out, "curvature --json")["estimator"]["neighbour_weights"], w);
    k[i++] = io::read_mesh(out).field->K;
  }
  ASSERT_EQ(k[0].size(), k[1].size());
  EXPECT_NE(k[0], k[1]) << "the weights change the least squares on a marching-cubes mesh";
  expect_clean_failure(run_isocurv({"curvature", dataset("torus"), "--batagelo-weights", "inverse-square", "-o",
                                    dir / "x.vtp"}),
                       "--estimator batagelo");
  expect_usage_error(run_isocurv({"curvature", dataset("torus"), "--estimator", "batagelo", "--batagelo-weights",
                                  "cubed", "-o", dir / "y.vtp"}),
                     "--batagelo-weights");
}

}  // namespace
