// Animated meshes against exact curvature: the affine ellipsoid sequence against an independently
// meshed ellipsoid, and frame coherence of the principal directions under a rigid rotation
// (Griffin's Max Triangle ID purpose, G-MAXID).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <cmath>
#include <vector>

#include "curvature/estimate.h"
#include "curvature/topology.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "deform/affine.h"
#include "mc/extract.h"
#include "volume/gradient_normals.h"
#include "tests/deform/deform_fixtures.h"

namespace isocurv {
namespace {

struct Errors {
  double H, K;
};

// Relative RMS of H and K of `f` against the exact curvature of `field` at the vertices `p`,
// each first projected onto the ellipsoid when `project` (marching-cubes vertices lie on the
// trilinear surface, a fraction of a voxel off it; the deformed sphere's lie on it to float
// precision).
Errors ellipsoid_errors(const Positions& p, const curvature::CurvatureField& f,
                        const datasets::Field& field, bool project) {
  std::vector<double> H, K, He, Ke;
  for (std::size_t i = 0; i < p.size(); ++i) {
    Eigen::Vector3d q(p[i][0], p[i][1], p[i][2]);
    if (project) q = datasets::project_to_surface(field, q);
    const datasets::SurfaceCurvature c = datasets::exact_curvature(field, q);
    H.push_back(f.H[i]), K.push_back(f.K[i]), He.push_back(c.H), Ke.push_back(c.K);
  }
  return {test::relative_rms(H, He), test::relative_rms(K, Ke)};
}

TEST(AffineEllipsoidSequence, PerFrameErrorsBeatAnIndependentlyMeshedEllipsoid) {
  // 60 frames, axes in [0.5, 1.5]: the sphere scaled on the device, curvature on the prepared
  // topology from the positions the kernel wrote, against the exact curvature of the ellipsoid
  // at those positions. The comparison (SEEDS-SPEC G-DEF2: "a static ellipsoid mesh with the
  // same axes") is an independently meshed one: marching cubes of the analytic ellipsoid field
  // at 80^3 (9.5k-13k vertices against the sphere's 10242) with the volume's gradient normals,
  // i.e. what `isocurv extract` gives for that shape, estimated by the same estimator. The spec's
  // "ratio within 1 +- 0.05" only holds for the scaled mesh against itself (ratio exactly 1:
  // bit-identical, which prepared_test checks); against another mesh the errors differ by the
  // meshes' quality, so the bounds here are measured ones with a 1.5x margin:
  //  - the deformed sphere (near-regular triangles, at most 3:1 stretched) is far more accurate
  //    than the marching-cubes mesh: worst ratio 0.33 (H and K) over the frames, asserted < 0.5;
  //  - the marching-cubes ellipsoid itself: relative RMS H <= 0.037, K <= 0.051 at 80^3 (the
  //    estimator's known accuracy on MC meshes with volume normals, cf. Appendix A4: 0.0104 /
  //    0.0327 on the 64^3 torus, whose h * k_max is 0.13 against 0.18 here), asserted < 0.055,
  //    < 0.075;
  //  - the deformed sphere: H <= 0.0103, K <= 0.0140 (the 3:1 frames), asserted < 0.015, < 0.021.
  // A wrong frame (stale positions, the wrong topology, a bad matrix) gives errors of order 1.
  openvdb::initialize();
  Device& dev = test::device();
  const Mesh sphere = test::icosphere(5);  // 10242 vertices
  curvature::Topology topo = curvature::prepare(sphere.triangles, sphere.vertex_count(), dev);
  const cl::Buffer rest = test::to_device(sphere.positions);
  curvature::CurvatureField animated;
  double worst_ratio = 0, worst_a_h = 0, worst_a_k = 0, worst_m_h = 0, worst_m_k = 0;
  for (int f = 0; f < 60; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    const std::array<double, 3> axes = deform::ellipsoid_axes(f / 60.0);
    const auto field = datasets::make_ellipsoid(axes[0], axes[1], axes[2]);
    deform::affine(dev, rest, sphere.vertex_count(), deform::scaling(axes[0], axes[1], axes[2]),
                   topo.positions());
    curvature::estimate_resident(topo, dev, {}, animated);
    const Positions moved = test::from_device(topo.positions(), sphere.vertex_count());
    const Errors a = ellipsoid_errors(moved, animated, *field, false);

    const volume::Volume vol = datasets::sample(*field, 80);
    const Mesh mc_mesh = mc::extract(vol, float(field->isovalue()), dev);
    const std::vector<Vec3f> normals = volume::gradient_normals(vol, mc_mesh.positions);
    curvature::Options o;
    o.vertex_normals = &normals;
    const Errors m =
        ellipsoid_errors(mc_mesh.positions, curvature::estimate(mc_mesh, dev, o), *field, true);

    EXPECT_LT(a.H, 0.5 * m.H);
    EXPECT_LT(a.K, 0.5 * m.K);
    EXPECT_LT(m.H, 0.055);
    EXPECT_LT(m.K, 0.075);
    EXPECT_LT(a.H, 0.015);
    EXPECT_LT(a.K, 0.021);
    worst_ratio = std::max({worst_ratio, a.H / m.H, a.K / m.K});
    worst_a_h = std::max(worst_a_h, a.H), worst_a_k = std::max(worst_a_k, a.K);
    worst_m_h = std::max(worst_m_h, m.H), worst_m_k = std::max(worst_m_k, m.K);
  }
  std::printf(
      "affine ellipsoid, 60 frames: deformed sphere worst relative RMS H %.4f K %.4f; "
      "marching cubes 80^3 worst H %.4f K %.4f; worst ratio %.3f\n",
      worst_a_h, worst_a_k, worst_m_h, worst_m_k, worst_ratio);
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
