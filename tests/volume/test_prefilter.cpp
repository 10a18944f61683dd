// The volume estimator's reconstruction: the prefilter's taps (volume/prefilter.h), the brick
// plan and the double-precision passes against a brute-force dense convolution, the quartic
// B-spline's weights (volume/spline_jet.h), and the whole reconstruction on a cubic field, where
// it must equal Gaussian smoothing exactly.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.h"
#include "cubic_field.h"
#include "volume/from_dense.h"
#include "volume/prefilter.h"
#include "volume/spline_jet.h"

using namespace isocurv;
using namespace isocurv::volume;

namespace {

double variance_of(const PrefilterTaps& t) {
  double v = 0;
  for (int k = -t.radius; k <= t.radius; ++k) v += double(k) * k * t.w[k + t.radius];
  return v;
}

Volume dense_volume(const std::array<int, 3>& dims, const std::vector<float>& data,
                    openvdb::math::Transform::Ptr xform) {
  DenseSource src;
  src.path = "test";
  src.format = "generated";
  src.voxel_type = "float";
  return from_dense(data.data(), dims, xform, src);
}

// S at voxel v by the definition: the separable prefilter of the samples, read at coordinates
// clamped to the domain (dense) or from the grid as it is (sparse).
double brute_force_smoothed(const openvdb::FloatGrid& grid, const SmoothingPlan& plan,
                            const openvdb::Coord& v) {
  auto acc = grid.getConstAccessor();
  const GridFrame& f = plan.frame;
  double sum = 0;
  for (int k = -plan.taps[2].radius; k <= plan.taps[2].radius; ++k)
    for (int j = -plan.taps[1].radius; j <= plan.taps[1].radius; ++j)
      for (int i = -plan.taps[0].radius; i <= plan.taps[0].radius; ++i) {
        openvdb::Coord c = v + openvdb::Coord(i, j, k);
        if (f.clamp)
          for (int a = 0; a < 3; ++a) c[a] = std::clamp(c[a], f.lo[a], f.hi[a]);
        sum += plan.taps[0].w[i + plan.taps[0].radius] * plan.taps[1].w[j + plan.taps[1].radius] *
               plan.taps[2].w[k + plan.taps[2].radius] * acc.getValue(c);
      }
  return sum;
}

// Every voxel of stage 3 of `plan`, smoothed by smooth_reference, against the brute force.
double worst_smoothing_error(const openvdb::FloatGrid& grid, const SmoothingPlan& plan) {
  const SmoothedSamples s = smooth_reference(grid, plan);
  double worst = 0;
  const std::vector<openvdb::Coord>& bricks = plan.stages[3].bricks;
  for (std::size_t b = 0; b < bricks.size(); ++b)
    for (int v = 0; v < 512; v += 7) {  // every 7th voxel keeps the brute force quick
      const openvdb::Coord c(bricks[b][0] * 8 + (v & 7), bricks[b][1] * 8 + ((v >> 3) & 7),
                             bricks[b][2] * 8 + (v >> 6));
      worst =
          std::max(worst, std::abs(s.samples[b * 512 + v] - brute_force_smoothed(grid, plan, c)));
    }
  return worst;
}

}  // namespace

TEST(Prefilter, TapsSumToOneWithTheAskedVariance) {
  for (double variance : {0.005, 0.05, 0.2, 0.5833, 3.58, 35.58}) {
    const PrefilterTaps t = prefilter_taps(variance);
    ASSERT_EQ(t.w.size(), std::size_t(2 * t.radius + 1));
    EXPECT_LE(t.radius, kPrefilterMaxRadius);
    double sum = 0;
    for (double w : t.w) sum += w;
    EXPECT_NEAR(sum, 1.0, 1e-12) << variance;
    for (int k = 1; k <= t.radius; ++k) EXPECT_DOUBLE_EQ(t.w[t.radius + k], t.w[t.radius - k]);
    EXPECT_NEAR(variance_of(t), variance, 1e-9 * variance) << variance;
  }
  // A Gaussian sampled at deviation sqrt(0.2) has variance 0.141 (its neighbours weigh 0.0705
  // each): the taps' deviation is raised until the variance is 0.2 (neighbours near 0.1).
  const PrefilterTaps small = prefilter_taps(0.2);
  EXPECT_GT(small.w[small.radius + 1], 0.09);
  EXPECT_EQ(prefilter_taps(0).radius, 0);
  EXPECT_THROW(prefilter_taps(-0.1), Error);
  EXPECT_THROW(prefilter_taps(std::nan("")), Error);
}

TEST(SplineWeights, PartitionMomentsDerivativesAndContinuity) {
  for (double q : {-7.3, -0.5, 0.0, 0.25, 0.5, 0.999, 3.5, 17.75}) {
    const SplineWeights w = spline_weights(q);
    EXPECT_LE(w.first, q - 1.5 + 1e-12);
    EXPECT_GT(w.first, q - 2.5 - 1e-12);
    double sum[4] = {}, m1 = 0, m2 = 0, m3 = 0;
    for (int t = 0; t < 5; ++t) {
      const double d = w.first + t - q;
      for (int n = 0; n < 4; ++n) sum[n] += w.w[n][t];
      m1 += w.w[0][t] * d, m2 += w.w[0][t] * d * d, m3 += w.w[0][t] * d * d * d;
      EXPECT_GE(w.w[0][t], 0.0);
    }
    EXPECT_NEAR(sum[0], 1.0, 1e-12) << q;
    for (int n = 1; n < 4; ++n) EXPECT_NEAR(sum[n], 0.0, 1e-12) << q << " order " << n;
    EXPECT_NEAR(m1, 0.0, 1e-12) << q;
    EXPECT_NEAR(m2, kSplineVariance, 1e-12) << q;  // Strang-Fix: moments do not depend on q
    EXPECT_NEAR(m3, 0.0, 1e-12) << q;
    // Each order is the derivative of the one below (central differences, by tap index).
    const double h = 1e-5;
    const SplineWeights a = spline_weights(q - h), b = spline_weights(q + h);
    auto at = [](const SplineWeights& s, int n, int tap) {
      const int t = tap - s.first;
      return t >= 0 && t < 5 ? s.w[n][t] : 0.0;
    };
    for (int tap = w.first - 1; tap <= w.first + 5; ++tap)
      for (int n = 0; n < 3; ++n)
        EXPECT_NEAR((at(b, n, tap) - at(a, n, tap)) / (2 * h), at(w, n + 1, tap), 1e-4)
            << q << " tap " << tap << " order " << n + 1;
  }
  // C3: even the third derivative is continuous across a knot (the half-integers).
  for (double knot : {-0.5, 0.5, 2.5}) {
    const SplineWeights l = spline_weights(knot - 1e-9), r = spline_weights(knot + 1e-9);
    for (int tap = l.first - 1; tap <= l.first + 5; ++tap) {
      const int tl = tap - l.first, tr = tap - r.first;
      const double wl = tl >= 0 && tl < 5 ? l.w[3][tl] : 0, wr = tr >= 0 && tr < 5 ? r.w[3][tr] : 0;
      EXPECT_NEAR(wl, wr, 1e-6) << knot << " tap " << tap;
    }
  }
}

// The three passes on the plan's bricks equal the prefilter applied directly to the samples,
// for a dense volume (coordinates clamped to the domain, vertices near its border) with
// anisotropic spacing, and for a sparse grid (background outside its leaves).
TEST(Prefilter, PassesEqualTheDirectConvolution) {
  const std::array<int, 3> dims{21, 18, 13};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uni(0.0f, 100.0f);
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  for (float& v : data) v = uni(rng);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(1.0, 1.5, 2.0));
  const Volume dense = dense_volume(dims, data, xform);
  const GridFrame frame = grid_frame(dense);
  ASSERT_TRUE(frame.clamp);
  // World points: a corner of the domain, the middle of a face, the centre.
  const Positions points = {{0.2f, 0.1f, 0.3f}, {10.0f, 0.5f, 12.0f}, {10.4f, 13.0f, 12.9f}};
  const SmoothingPlan plan = plan_smoothing(frame, points, openvdb::Vec3d(2.0, 1.4, 1.0), 2.0);
  EXPECT_GT(plan.taps[0].radius, plan.taps[2].radius) << "a world scale is more voxels along x";
  for (const BrickSet& s : plan.stages) EXPECT_FALSE(s.bricks.empty());
  EXPECT_LT(worst_smoothing_error(*dense.grid, plan), 1e-9);

  openvdb::FloatGrid::Ptr sparse = openvdb::FloatGrid::create(-5.0f);
  auto acc = sparse->getAccessor();
  for (int z = 0; z < 12; ++z)
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x)
        if (x + y + z < 20) acc.setValue(openvdb::Coord(x, y, z), uni(rng));
  Volume v;
  v.grid = sparse;
  v.dense = false;
  const GridFrame sf = grid_frame(v);
  ASSERT_FALSE(sf.clamp);
  const SmoothingPlan sp =
      plan_smoothing(sf, {{3.0f, 4.0f, 5.0f}, {11.5f, 2.0f, 0.0f}}, openvdb::Vec3d(1, 1, 1), 1.3);
  EXPECT_LT(worst_smoothing_error(*sparse, sp), 1e-9);
}

// On a cubic field the reconstruction is exact: smoothing by any kernel of covariance sigma^2 I
// with no odd moments turns p into p + sigma^2 / 2 Laplacian(p), and the prefilter and the
// B-spline together are such a kernel (their moments add; both are exact up to the fourth). The
// grid is rotated and anisotropic, so this also checks the world transform of every derivative.
TEST(SplineJet, CubicFieldGivesTheGaussianSmoothedCubic) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const test::RandomCubic p(rng, uni, openvdb::Vec3d(20, 24, 30), 0.2, 0.01);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(0.8, 1.0, 1.3));
  xform->postRotate(0.4, openvdb::math::Z_AXIS);
  xform->postRotate(0.3, openvdb::math::X_AXIS);
  xform->postTranslate(openvdb::Vec3d(5, 9, 14));
  const std::array<int, 3> dims{48, 48, 48};
  const Volume vol = dense_volume(dims, p.sample(*xform, dims), xform);
  const GridFrame frame = grid_frame(vol);

  for (double sigma : {1.3, 2.2}) {
    Positions points;
    for (int i = 0; i < 6; ++i) {
      const openvdb::Vec3d w = xform->indexToWorld(
          openvdb::Vec3d(22 + 4 * uni(rng), 22 + 4 * uni(rng), 22 + 4 * uni(rng)));
      points.push_back({float(w[0]), float(w[1]), float(w[2])});
    }
    const SmoothingPlan plan = plan_smoothing(frame, points, openvdb::Vec3d(0, 0, 0), sigma);
    const SmoothedSamples s = smooth_reference(*vol.grid, plan);
    for (const Vec3f& q : points) {
      // The world position of the float point, which is where the plan's window lies.
      const openvdb::Vec3d w(q[0], q[1], q[2]);
      test::expect_jet_near(spline_jet(s, w, 3), p.smoothed(w, sigma), {2e-4, 1e-4, 1e-4, 1e-4},
                            "sigma " + std::to_string(sigma));
    }
  }
}

TEST(Prefilter, ScaleBelowTheSplinesOwnIsAnError) {
  Volume v;
  v.grid = openvdb::FloatGrid::create(0.0f);
  const GridFrame f = grid_frame(v);
  EXPECT_THROW(plan_smoothing(f, {{0, 0, 0}}, openvdb::Vec3d(1, 1, 1), 0.6), Error);
  EXPECT_NO_THROW(plan_smoothing(f, {{0, 0, 0}}, openvdb::Vec3d(1, 1, 1), kMinScaleVoxels));
}
