// curvature::weld_duplicates: a mesh stored triangle by triangle (each with its own corners)
// estimates like the indexed one once welded; unwelded it has no curvature at all.
#include "curvature/weld.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {


TEST(Weld, UnweldedSphereGetsItsCurvatureBack) {
  const Mesh sphere = icosphere(3, 2.0f);
  Mesh m = unwelded(sphere);
  const curvature::CurvatureField before = curvature::estimate(m, Device::default_device());
  double most = 0;
  for (float h : before.H) most = std::max(most, double(std::fabs(h)));
  EXPECT_LT(most, 1e-6) << "separate triangles are flat";

  EXPECT_EQ(curvature::weld_duplicates(m), 3 * sphere.triangles.size() - sphere.positions.size());
  ASSERT_EQ(m.positions.size(), sphere.positions.size());
  const curvature::CurvatureField after = curvature::estimate(m, Device::default_device());
  for (float h : after.H) ASSERT_NEAR(h, 0.5, 0.02);
  EXPECT_EQ(curvature::weld_duplicates(m), 0u) << "nothing left to weld";
}

TEST(Weld, NegativeZeroAndKeepsOutOfRangeIndices) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {-0.0f, 0, -0.0f}, {0, 1, 0}};
  m.triangles = {{0, 1, 3}, {2, 3, 9}};
  m.edge_keys = {1, 2, 3, 4};
  EXPECT_EQ(curvature::weld_duplicates(m), 1u);
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.triangles[0], (Tri{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (Tri{0, 2, 9})) << "an index out of range stays out of range";
  EXPECT_TRUE(m.edge_keys.empty());
}

}  // namespace
}  // namespace isocurv::test
