// The float OpenCL kernels against the double reference on the same meshes.
#include <gtest/gtest.h>

#include <cmath>

#include "compare.h"
#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;

// Kernels and reference agree to float precision: the relative RMS of k1, k2, H, K below 1e-5
// and principal directions within 1e-3 rad wherever k1 - k2 exceeds `gap`.
void expect_agreement(const Mesh& mesh, double gap, const curvature::Options& options = {}) {
  const CurvatureField ref = curvature::estimate_reference(mesh, options);
  const CurvatureField cl = curvature::estimate(mesh, Device::default_device(), options);
  ASSERT_EQ(cl.size(), mesh.vertex_count());
  const FieldDifference d = compare(cl, ref, gap);
  std::printf("  %zu vertices: %s\n", mesh.vertex_count(), d.str().c_str());
  EXPECT_LT(d.k1, 1e-5);
  EXPECT_LT(d.k2, 1e-5);
  EXPECT_LT(d.H, 1e-5);
  EXPECT_LT(d.K, 1e-5);
  EXPECT_LT(d.dir_angle, 1e-3);
  EXPECT_LT(d.area, 1e-6);
  EXPECT_LT(d.normal_angle, 1e-5);
  EXPECT_LT(d.dcurv, 1e-3);
  EXPECT_TRUE(d.same_boundary);
  EXPECT_TRUE(all_finite(cl));
}

TEST(KernelVsReference, Icosphere) { expect_agreement(icosphere(5, 1.5f), 1e-2); }

TEST(KernelVsReference, Torus) {
  const Torus t = torus(1.0, 0.35, 200, 80);
  expect_agreement(t.mesh, 0.05);
}

TEST(KernelVsReference, TorusAreaWeights) {
  curvature::Options o;
  o.normal_weights = curvature::NormalWeights::area;
  expect_agreement(torus(1.0, 0.35, 120, 48).mesh, 0.05, o);
}

TEST(KernelVsReference, TorusGivenNormals) {
  const Torus t = torus(1.0, 0.35, 120, 48);
  std::vector<Vec3f> normals;
  for (std::size_t i = 0; i < t.mesh.vertex_count(); ++i) {
    const Eigen::Vector3d n = t.normal(i);
    normals.push_back({float(n.x()), float(n.y()), float(n.z())});
  }
  curvature::Options o;
  o.vertex_normals = &normals;
  expect_agreement(t.mesh, 0.05, o);
}

TEST(KernelVsReference, SaddlePatchWithBoundary) {
  expect_agreement(quadric_patch(101, 1.0f, 1.5f, -0.7f), 0.05);
}

}  // namespace
}  // namespace isocurv::test
