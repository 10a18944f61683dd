// Animated meshes against exact curvature: the affine ellipsoid sequence, and frame coherence of
// the principal directions under a rigid rotation (Griffin's Max Triangle ID purpose, G-MAXID).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "curvature/estimate.h"
#include "curvature/topology.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "deform/affine.h"
#include "tests/deform/deform_fixtures.h"

namespace isocurv {
namespace {

struct Errors {
  double H, K;
};

// Relative RMS of H and K of `f` against the exact curvature of the ellipsoid (a, b, c) at the
// vertices `p` (which lie on it to float precision).
Errors ellipsoid_errors(const Positions& p, const curvature::CurvatureField& f,
                        const std::array<double, 3>& axes) {
  const auto field = datasets::make_ellipsoid(axes[0], axes[1], axes[2]);
  std::vector<double> H, K, He, Ke;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const datasets::SurfaceCurvature c =
        datasets::exact_curvature(*field, Eigen::Vector3d(p[i][0], p[i][1], p[i][2]));
    H.push_back(f.H[i]), K.push_back(f.K[i]), He.push_back(c.H), Ke.push_back(c.K);
  }
  return {test::relative_rms(H, He), test::relative_rms(K, Ke)};
}

TEST(AffineEllipsoidSequence, PerFrameErrorsEqualTheStaticEllipsoid) {
  // 60 frames, axes in [0.5, 1.5]: the sphere scaled on the device, curvature on the prepared
  // topology from the positions the kernel wrote; the static mesh: the same axes applied on the
  // host, a cold estimate.
  Device& dev = test::device();
  const Mesh sphere = test::icosphere(5);  // 10242 vertices
  curvature::Topology topo = curvature::prepare(sphere.triangles, sphere.vertex_count(), dev);
  const cl::Buffer rest = test::to_device(sphere.positions);
  curvature::CurvatureField animated;
  double worst = 0, worst_h = 0;
  for (int f = 0; f < 60; ++f) {
    const std::array<double, 3> axes = deform::ellipsoid_axes(f / 60.0);
    const deform::Affine m = deform::scaling(axes[0], axes[1], axes[2]);
    deform::affine(dev, rest, sphere.vertex_count(), m, topo.positions());
    curvature::estimate_resident(topo, dev, {}, animated);
    const Positions moved = test::from_device(topo.positions(), sphere.vertex_count());
    const Errors a = ellipsoid_errors(moved, animated, axes);

    Mesh still = sphere;
    still.positions = deform::affine_reference(sphere.positions, m);
    const Errors s = ellipsoid_errors(still.positions, curvature::estimate(still, dev), axes);
    SCOPED_TRACE("frame " + std::to_string(f));
    EXPECT_NEAR(a.H / s.H, 1.0, 0.05);
    EXPECT_NEAR(a.K / s.K, 1.0, 0.05);
    EXPECT_LT(s.H, 0.05);  // the estimate is meaningful at this resolution
    worst = std::max({worst, std::abs(a.H / s.H - 1), std::abs(a.K / s.K - 1)});
    worst_h = std::max(worst_h, a.H);
  }
  std::printf("affine ellipsoid: worst per-frame |ratio - 1| %.2e, worst H relative RMS %.4f\n",
              worst, worst_h);
}

Eigen::Vector3d v3(const Vec3f& v) { return {v[0], v[1], v[2]}; }

TEST(FrameCoherence, PrincipalDirectionsRotateWithTheMesh) {
  Device& dev = test::device();
  Mesh m = test::icosphere(4);
  m.positions = deform::affine_reference(m.positions, deform::scaling(1.0, 0.7, 0.45));
  curvature::Topology topo = curvature::prepare(m.triangles, m.vertex_count(), dev);
  curvature::CurvatureField before, after;
  curvature::estimate(m.positions, topo, dev, {}, before);
  const cl::Buffer rest = test::to_device(m.positions);
  const std::array<double, 3> axis{1, 2, 3};
  const double angle = 0.7;
  deform::affine(dev, rest, m.vertex_count(), deform::rotation(axis, angle), topo.positions());
  curvature::estimate_resident(topo, dev, {}, after);
  // R in double, as the kernel's float matrix.
  const deform::Affine rf = deform::rotation(axis, angle);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = rf[4 * r + c];
  double max_curvedness = 0;
  for (float c : before.curvedness) max_curvedness = std::max(max_curvedness, double(c));
  std::size_t tested = 0;
  double worst = 0;
  for (std::size_t i = 0; i < m.vertex_count(); ++i) {
    if (!(before.k1[i] - before.k2[i] > 1e-2 * max_curvedness)) continue;
    const Eigen::Vector3d expect = R * v3(before.dir1[i]), got = v3(after.dir1[i]);
    const double angle_err = std::atan2(expect.cross(got).norm(), std::abs(expect.dot(got)));
    worst = std::max(worst, angle_err);
    ++tested;
  }
  std::printf("frame coherence: %zu of %zu vertices tested, worst dir1 angle %.2e rad\n", tested,
              m.vertex_count(), worst);
  EXPECT_GT(tested, m.vertex_count() / 2);
  EXPECT_LE(worst, 1e-4);
}

}  // namespace
}  // namespace isocurv
