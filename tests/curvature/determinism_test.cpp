// Bit-identical results across runs, and the step timings on the largest test mesh.
#include <gtest/gtest.h>

#include <chrono>

#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

TEST(Determinism, TwoRunsAreBitIdentical) {
  const Torus t = torus(1.0, 0.3, 300, 100, 0.3);
  Device& d = Device::default_device();
  const curvature::CurvatureField a = curvature::estimate(t.mesh, d);
  const curvature::CurvatureField b = curvature::estimate(icosphere(2), d);  // reuse buffers
  const curvature::CurvatureField c = curvature::estimate(t.mesh, d);
  (void)b;
  EXPECT_TRUE(bit_identical(a, c));
  EXPECT_TRUE(bit_identical(curvature::estimate_reference(t.mesh),
                            curvature::estimate_reference(t.mesh)));
}

// Prints the kernel and reference times on a ~200k-vertex mesh (the benchmark's size); asserts
// nothing about speed, which depends on the machine and its load.
TEST(Timing, LargeTorus) {
  const Torus t = torus(1.0, 0.3, 640, 320, 0.3);
  Device& d = Device::default_device();
  curvature::CurvatureField field;
  curvature::Timings tm, step;
  for (int i = 0; i < 2; ++i) curvature::estimate(t.mesh, d, {}, field);  // build, buffers
  double fresh = 1e9, reused = 1e9;
  for (int i = 0; i < 5; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    const curvature::CurvatureField f = curvature::estimate(t.mesh, d);
    fresh = std::min(fresh, ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    curvature::estimate(t.mesh, d, {}, field);
    reused = std::min(reused, ms_since(t0));
    curvature::estimate(t.mesh, d, {}, field, &step);
    if (i == 0 || step.total < tm.total) tm = step;
  }
  const auto t0 = std::chrono::steady_clock::now();
  curvature::estimate_reference(t.mesh);
  const double ref = ms_since(t0);
  std::printf("  %zu vertices, %zu triangles on %s\n", t.mesh.vertex_count(),
              t.mesh.triangle_count(), d.info().name.c_str());
  std::printf("  steps separated (ms): adjacency %.1f, upload %.1f, normals+areas %.1f, "
              "tensor %.1f, directions %.1f, derivative %.1f, download %.1f, total %.1f\n",
              tm.adjacency, tm.upload, tm.normals_areas, tm.tensor, tm.directions, tm.derivative,
              tm.download, tm.total);
  std::printf("  best of 5 (ms): new field %.1f, reused field %.1f; double reference %.1f "
              "(%.1fx, %.1fx)\n", fresh, reused, ref, ref / fresh, ref / reused);
}

}  // namespace
}  // namespace isocurv::test
