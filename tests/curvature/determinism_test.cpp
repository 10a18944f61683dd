// Bit-identical results across runs, and the step timings on the largest test mesh.
#include <gtest/gtest.h>

#include <chrono>

#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

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
// nothing about speed, which depends on the machine.
TEST(Timing, LargeTorus) {
  const Torus t = torus(1.0, 0.3, 640, 320, 0.3);
  Device& d = Device::default_device();
  curvature::Timings tm;
  for (int i = 0; i < 3; ++i) curvature::estimate(t.mesh, d, {}, &tm);  // warm: build, buffers
  double best = 1e9;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    curvature::estimate(t.mesh, d);
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  const auto t0 = std::chrono::steady_clock::now();
  curvature::estimate_reference(t.mesh);
  const double ref = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("  %zu vertices, %zu triangles on %s\n", t.mesh.vertex_count(), t.mesh.triangle_count(),
              d.info().name.c_str());
  std::printf("  kernels, steps separated (ms): adjacency %.1f, upload %.1f, normals+areas %.1f, "
              "tensor %.1f, directions %.1f, derivative %.1f, download %.1f, total %.1f\n",
              tm.adjacency, tm.upload, tm.normals_areas, tm.tensor, tm.directions, tm.derivative,
              tm.download, tm.total);
  std::printf("  kernels, best of 5 (ms): %.1f; double reference: %.1f (%.1fx)\n", best, ref, ref / best);
}

}  // namespace
}  // namespace isocurv::test
