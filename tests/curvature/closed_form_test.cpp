// Kernels and reference against closed-form curvature: sphere, torus, quadric patches.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/cl_device.h"
#include "curvature/derived.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;
using Estimator = std::function<CurvatureField(const Mesh&, const curvature::Options&)>;

const Estimator kKernels = [](const Mesh& m, const curvature::Options& o) {
  return curvature::estimate(m, Device::default_device(), o);
};
const Estimator kReference = [](const Mesh& m, const curvature::Options& o) {
  return curvature::estimate_reference(m, o);
};

class ClosedForm : public ::testing::TestWithParam<bool> {  // true: kernels, false: reference
 protected:
  CurvatureField run(const Mesh& m, const curvature::Options& o = {}) const {
    return (GetParam() ? kKernels : kReference)(m, o);
  }
};

// Outward normals on a sphere of radius R give k1 = k2 = H = +1/R. With Max's weights the vertex
// normals of an inscribed mesh are exact, hence so is the curvature (to rounding).
TEST_P(ClosedForm, SphereIsPositiveOneOverR) {
  const float R = 2.0f;
  const CurvatureField f = run(icosphere(4, R));
  double total_area = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    ASSERT_NEAR(f.k1[i], 1 / R, 2e-5);
    ASSERT_NEAR(f.k2[i], 1 / R, 2e-5);
    ASSERT_NEAR(f.H[i], 1 / R, 2e-5);
    ASSERT_NEAR(f.K[i], 1 / (R * R), 2e-5);
    ASSERT_NEAR(f.shape_index[i], 1.0f, 1e-3);
    ASSERT_NEAR(f.curvedness[i], 1 / R, 2e-5);
    ASSERT_NEAR(f.ao[i], curvature::ambient_occlusion(0.5, 0.5, 1.0), 1e-5);
    ASSERT_EQ(f.boundary[i], 0);
    total_area += f.area[i];
    const Vec3f& n = f.normals[i];
    ASSERT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6);
  }
  // The mixed areas partition the inscribed polyhedron's area, a little below 4 pi R^2.
  EXPECT_NEAR(total_area, 4 * M_PI * R * R, 4 * M_PI * R * R * 5e-3);
}

// Reversed winding makes the normals point inwards: every curvature changes sign.
TEST_P(ClosedForm, InvertedSphereIsNegative) {
  Mesh m = icosphere(3, 0.5f);
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  const CurvatureField f = run(m);
  for (std::size_t i = 0; i < f.size(); ++i) {
    ASSERT_NEAR(f.k1[i], -2.0f, 1e-4);
    ASSERT_NEAR(f.k2[i], -2.0f, 1e-4);
    ASSERT_NEAR(f.shape_index[i], -1.0f, 1e-3);
  }
}

// A paraboloid cup z = (x^2 + y^2) / 2 with normals up (into the cup) is concave: k = -1 at the
// bottom; the saddle z = (x^2 - 0.5 y^2) / 2 has k1 = 0.5, k2 = -1 there, dir1 along y.
TEST_P(ClosedForm, QuadricPatchAtOrigin) {
  const int n = 61;  // the origin is vertex (30, 30)
  const std::size_t o = 30 * n + 30;
  const CurvatureField cup = run(quadric_patch(n, 0.3f, 1.0f, 1.0f));
  EXPECT_NEAR(cup.k1[o], -1.0, 1e-3);
  EXPECT_NEAR(cup.k2[o], -1.0, 1e-3);
  const CurvatureField saddle = run(quadric_patch(n, 0.3f, 1.0f, -0.5f));
  EXPECT_NEAR(saddle.k1[o], 0.5, 1e-3);
  EXPECT_NEAR(saddle.k2[o], -1.0, 1e-3);
  EXPECT_NEAR(std::abs(saddle.dir1[o][1]), 1.0, 1e-4);
  EXPECT_NEAR(std::abs(saddle.dir2[o][0]), 1.0, 1e-4);
  EXPECT_LT(saddle.K[o], 0);
}

struct TorusError {
  double k1, k2, H, K, dcurv;
};

TorusError torus_error(const ClosedForm& test, const Torus& t, const curvature::Options& o = {}) {
  const CurvatureField f = test.GetParam() ? kKernels(t.mesh, o) : kReference(t.mesh, o);
  std::vector<double> x[5], ref[5];
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double k1 = t.k1(i), k2 = t.k2(i);
    const Eigen::Vector3d d1(f.dir1[i][0], f.dir1[i][1], f.dir1[i][2]);
    const double sign = d1.dot(t.tube_dir(i)) < 0 ? -1 : 1;
    const double est[5] = {f.k1[i], f.k2[i], f.H[i], f.K[i], sign * f.dcurv[i][2]};
    const double exact[5] = {k1, k2, (k1 + k2) / 2, k1 * k2, t.dk2_along_tube(i)};
    for (int q = 0; q < 5; ++q) x[q].push_back(est[q]), ref[q].push_back(exact[q]);
  }
  return {relative_rms(x[0], ref[0]), relative_rms(x[1], ref[1]), relative_rms(x[2], ref[2]),
          relative_rms(x[3], ref[3]), relative_rms(x[4], ref[4])};
}

// On the torus grid the error of k1, k2, H, K falls as the grid is refined, at second order (each
// doubling divides it by 4.0 here): the estimator is exact for quadrics up to the O(h^2) chord
// terms of the edges, so the error scales as (h k)^2, about 4e-3 for the finest grid's
// h = 2 pi r / 96 and k2 = 2.5. The absolute bounds are the finest grid's measured errors plus
// 50% (k1 1.1e-4, k2 1.0e-3, H 2.8e-4, K 1.1e-3 measured; float and double agree to 1e-6).
TEST_P(ClosedForm, TorusConvergesToClosedForm) {
  TorusError prev{};
  const int sizes[3][2] = {{60, 24}, {120, 48}, {240, 96}};
  for (int s = 0; s < 3; ++s) {
    const TorusError e = torus_error(*this, torus(1.0, 0.4, sizes[s][0], sizes[s][1]));
    std::printf("  torus %dx%d: relative RMS k1 %.3g, k2 %.3g, H %.3g, K %.3g, dcurv C122 %.3g\n",
                sizes[s][0], sizes[s][1], e.k1, e.k2, e.H, e.K, e.dcurv);
    if (s > 0) {
      EXPECT_LT(e.k1, 0.35 * prev.k1);
      EXPECT_LT(e.k2, 0.35 * prev.k2);
      EXPECT_LT(e.H, 0.35 * prev.H);
      EXPECT_LT(e.K, 0.35 * prev.K);
      EXPECT_LT(e.dcurv, 0.7 * prev.dcurv);
    }
    prev = e;
  }
  EXPECT_LT(prev.k1, 1.7e-4);
  EXPECT_LT(prev.k2, 1.6e-3);
  EXPECT_LT(prev.H, 4.2e-4);
  EXPECT_LT(prev.K, 1.7e-3);
  EXPECT_LT(prev.dcurv, 3e-3);
}

// Exact normals supplied from outside (as the volume gradient would give) beat the mesh normals
// on an irregular mesh. (On the regular grid Max's normals are already exact to 3e-7.)
TEST_P(ClosedForm, GivenNormalsBeatMeshNormalsOnJitteredTorus) {
  const Torus t = torus(1.0, 0.4, 120, 48, 0.3);
  std::vector<Vec3f> normals;
  for (std::size_t i = 0; i < t.mesh.vertex_count(); ++i) {
    const Eigen::Vector3d n = t.normal(i);
    normals.push_back({float(n.x()), float(n.y()), float(n.z())});
  }
  curvature::Options given;
  given.vertex_normals = &normals;
  const TorusError mesh_n = torus_error(*this, t), exact_n = torus_error(*this, t, given);
  std::printf("  jittered torus 120x48 relative RMS: H %.3g, K %.3g with mesh normals; H %.3g, "
              "K %.3g with exact normals\n", mesh_n.H, mesh_n.K, exact_n.H, exact_n.K);
  EXPECT_LT(exact_n.H, 0.5 * mesh_n.H);
  EXPECT_LT(exact_n.K, 0.5 * mesh_n.K);
}

INSTANTIATE_TEST_SUITE_P(Curvature, ClosedForm, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "Kernels" : "Reference"; });

}  // namespace
}  // namespace isocurv::test
