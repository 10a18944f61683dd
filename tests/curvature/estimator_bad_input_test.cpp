// The new mesh estimators on degenerate input: an empty mesh, a single triangle, a fan of slivers,
// an open boundary, an isolated vertex and invalid indices. Finite values and flags, never a crash.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.h"
#include "curvature/batagelo.h"
#include "curvature/cubic_fit.h"
#include "curvature/meyer.h"
#include "curvature/normal_sampling.h"
#include "curvature/prantl.h"
#include "curvature/quadric_fit.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;
using Fn = std::function<CurvatureField(const Mesh&, const curvature::Options&)>;

struct Named {
  std::string name;
  Fn fn;
  bool fits;  // needs 3 neighbours (a least-squares fit over the 1-ring)
};
const std::vector<Named>& all() {
  static const std::vector<Named> e = {
      {"batagelo", curvature::estimate_batagelo_reference, false},
      {"prantl3",
       [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 3);
       },
       false},
      {"prantl2",
       [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_prantl_reference(m, o, 2, curvature::PrantlAveraging::uniform);
       },
       false},
      {"quadric", curvature::estimate_quadric_fit_reference, true},
      {"cubic", curvature::estimate_cubic_fit_reference, true},
      {"sampling", curvature::estimate_normal_sampling_reference, true},
      {"meyer", curvature::estimate_meyer_reference, false}};
  return e;
}

bool sizes_ok(const CurvatureField& f, std::size_t n) {
  return f.k1.size() == n && f.k2.size() == n && f.H.size() == n && f.K.size() == n &&
         f.normals.size() == n && f.area.size() == n && f.boundary.size() == n &&
         f.unreliable.size() == n;
}

TEST(EstimatorBadInput, EmptyMesh) {
  for (const Named& e : all()) {
    const CurvatureField f = e.fn(Mesh{}, {});
    EXPECT_EQ(f.size(), 0u) << e.name;
  }
}

TEST(EstimatorBadInput, SingleTriangleAndIsolatedVertex) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};  // vertex 3 is isolated
  m.triangles = {{0, 1, 2}};
  for (const Named& e : all()) {
    const CurvatureField f = e.fn(m, {});
    ASSERT_TRUE(sizes_ok(f, 4)) << e.name;
    EXPECT_TRUE(all_finite(f)) << e.name;
    EXPECT_EQ(f.unreliable[3], 1) << e.name;
    EXPECT_EQ(f.k1[3], 0) << e.name;
    for (int v = 0; v < 3; ++v) {
      EXPECT_EQ(f.boundary[v], 1) << e.name;
      // Two neighbours cannot determine a fit's three unknowns; the flat triangle is flat.
      if (e.fits) {
        EXPECT_EQ(f.unreliable[v], 1) << e.name;
      }
      if (e.name == "batagelo" || e.name == "prantl3" || e.name == "prantl2") {
        EXPECT_EQ(f.unreliable[v], 0) << e.name;
        EXPECT_NEAR(f.k1[v], 0, 1e-6) << e.name;
        EXPECT_NEAR(f.k2[v], 0, 1e-6) << e.name;
      }
    }
  }
}

// A fan of slivers around vertex 0: eight triangles whose outer corners lie almost on a line,
// plus a repeated-index triangle and a zero-area one.
TEST(EstimatorBadInput, SliverFan) {
  Mesh m;
  m.positions.push_back({0, 0, 0});
  for (int i = 0; i < 9; ++i) m.positions.push_back({1, float(i) * 1e-4f, float(i % 2) * 1e-5f});
  for (std::uint32_t i = 1; i < 9; ++i) m.triangles.push_back({0, i, i + 1});
  m.triangles.push_back({0, 0, 1});
  m.positions.push_back({2, 0, 0});
  m.triangles.push_back({1, 10, 1});
  for (const Named& e : all()) {
    const CurvatureField f = e.fn(m, {});
    ASSERT_TRUE(sizes_ok(f, m.vertex_count())) << e.name;
    EXPECT_TRUE(all_finite(f)) << e.name;
  }
}

// An open patch of a sphere: finite everywhere, Boundary on the rim, interior close to 1/R.
TEST(EstimatorBadInput, OpenBoundary) {
  const Mesh sphere = icosphere(3, 1.0f);
  Mesh cap;
  cap.positions = sphere.positions;
  for (const Tri& t : sphere.triangles)
    if (sphere.positions[t[0]][2] > 0.3f && sphere.positions[t[1]][2] > 0.3f &&
        sphere.positions[t[2]][2] > 0.3f)
      cap.triangles.push_back(t);
  for (const Named& e : all()) {
    const CurvatureField f = e.fn(cap, {});
    ASSERT_TRUE(sizes_ok(f, cap.vertex_count())) << e.name;
    EXPECT_TRUE(all_finite(f)) << e.name;
    std::size_t rim = 0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      rim += f.boundary[i];
      if (cap.positions[i][2] > 0.8f) {
        EXPECT_NEAR(f.H[i], 1.0, 0.1) << e.name << " vertex " << i;
      }
    }
    EXPECT_GT(rim, 10u) << e.name;
  }
}

TEST(EstimatorBadInput, InvalidInputThrows) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 7}};
  for (const Named& e : all()) EXPECT_THROW(e.fn(m, {}), Error) << e.name;
  m.triangles = {{0, 1, 2}};
  EXPECT_THROW(curvature::estimate_prantl_reference(m, {}, 4), Error);
}

}  // namespace
}  // namespace isocurv::test
