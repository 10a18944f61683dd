// The device mesher against VTK's vtkFlyingEdges3D on the same dense volumes.
#include <gtest/gtest.h>

#include "core/cl_device.h"
#include "mc/extract.h"
#include "mc/mesh_check.h"
#include "tests/mc/flying_edges.h"
#include "tests/mc/volumes.h"

using namespace isocurv;

namespace {

void compare(const volume::Volume& v, float iso) {
  mc::Options plain;  // Flying Edges does not snap vertices onto voxels
  plain.snap = 0;
  const Mesh m = mc::extract(v, iso, Device::default_device(), plain);
  const mc::MeshCheck c = mc::check_mesh(m);
  const test::FlyingEdgesSurface ref = test::flying_edges(v, iso);
  ASSERT_GT(ref.triangles, 0u);
  EXPECT_NEAR(double(m.positions.size()), double(ref.points), 0.005 * ref.points);
  EXPECT_NEAR(double(m.triangles.size()), double(ref.triangles), 0.005 * ref.triangles);
  EXPECT_NEAR(c.area, ref.area, 0.001 * ref.area);
  std::printf("isocurv %zu vertices %zu triangles area %.3f | flying edges %zu %zu %.3f\n", m.positions.size(),
              m.triangles.size(), c.area, ref.points, ref.triangles, ref.area);
}

}  // namespace

TEST(VtkCompare, SphereTorusAndGyroidAgreeWithFlyingEdges) {
  compare(test::ball(64, 25.3, 31.6), 0.0f);
  compare(test::sampled([](double x, double y, double z) { return test::torus_density(x - 40, y - 40, z - 20, 24, 9); },
                        {80, 80, 40}, {0.5, 0.5, 0.7}, {3, -2, 1}),
          0.0f);
  compare(test::sampled([](double x, double y, double z) {
            const double s = 2 * M_PI / 17;
            return float(std::sin(s * x) * std::cos(s * y) + std::sin(s * y) * std::cos(s * z) + std::sin(s * z) * std::cos(s * x));
          }, {70, 60, 50}),
          0.2f);
}
