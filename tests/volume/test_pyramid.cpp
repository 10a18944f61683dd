// The scale-space pyramid (volume/pyramid.h): its levels' frames and decimated axes, each level's
// samples against the definition (the finer level smoothed and sampled at every second index,
// clamped to the domain) computed densely, values that do not depend on which bricks were asked
// for, the level an evaluation reads, and the whole reconstruction at a coarse level on a cubic
// field, where it must equal Gaussian smoothing exactly.
#include "volume/pyramid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "volume/from_dense.h"
#include "volume/prefilter.h"
#include "volume/spline_jet.h"

using namespace isocurv;
using namespace isocurv::volume;

namespace {

Volume pyr_volume(const std::array<int, 3>& dims, const std::vector<float>& data,
                    openvdb::math::Transform::Ptr xform) {
  openvdb::initialize();
  DenseSource src;
  src.path = "test";
  src.format = "generated";
  src.voxel_type = "float";
  return from_dense(data.data(), dims, xform, src);
}

// A dense box of samples in double, x fastest, and its domain.
struct PyrDense {
  openvdb::Coord lo, hi;
  std::vector<double> v;
  int n(int a) const { return hi[a] - lo[a] + 1; }
  double at(openvdb::Coord c) const {  // clamped, as the pyramid reads a dense domain
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(c[a], lo[a], hi[a]);
    return v[(std::size_t(c[2] - lo[2]) * n(1) + (c[1] - lo[1])) * n(0) + (c[0] - lo[0])];
  }
};

// The definition: level k + 1 from level k, every sample of its domain, densely.
PyrDense pyr_next_level(const PyrDense& d, const std::array<bool, 3>& decimated) {
  const PrefilterTaps t = prefilter_taps(kPyramidVariance);
  PyrDense out;
  for (int a = 0; a < 3; ++a) {
    out.lo[a] = decimated[a] ? (d.lo[a] + 1) / 2 : d.lo[a];  // domains here start at 0
    out.hi[a] = decimated[a] ? d.hi[a] / 2 : d.hi[a];
  }
  out.v.resize(std::size_t(out.n(0)) * out.n(1) * out.n(2));
  std::size_t i = 0;
  for (int z = out.lo[2]; z <= out.hi[2]; ++z)
    for (int y = out.lo[1]; y <= out.hi[1]; ++y)
      for (int x = out.lo[0]; x <= out.hi[0]; ++x) {
        const openvdb::Coord j(x, y, z);
        openvdb::Coord c;
        for (int a = 0; a < 3; ++a) c[a] = decimated[a] ? 2 * j[a] : j[a];
        const int r[3] = {decimated[0] ? t.radius : 0, decimated[1] ? t.radius : 0,
                          decimated[2] ? t.radius : 0};
        auto w = [&](int a, int k) { return decimated[a] ? t.w[std::size_t(k + t.radius)] : 1.0; };
        double sum = 0;
        for (int kz = -r[2]; kz <= r[2]; ++kz)
          for (int ky = -r[1]; ky <= r[1]; ++ky)
            for (int kx = -r[0]; kx <= r[0]; ++kx)
              sum += w(0, kx) * w(1, ky) * w(2, kz) * d.at(c + openvdb::Coord(kx, ky, kz));
        out.v[i++] = sum;
      }
  return out;
}

std::vector<float> pyr_random(const std::array<int, 3>& dims, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  for (float& x : data) x = uni(rng);
  return data;
}

// Every brick of level k's domain.
std::vector<openvdb::Coord> pyr_all_bricks(const PyramidLevel& l) {
  std::vector<openvdb::Coord> b;
  for (int z = l.frame.lo[2] >> 3; z <= l.frame.hi[2] >> 3; ++z)
    for (int y = l.frame.lo[1] >> 3; y <= l.frame.hi[1] >> 3; ++y)
      for (int x = l.frame.lo[0] >> 3; x <= l.frame.hi[0] >> 3; ++x) b.push_back({x, y, z});
  return b;
}

}  // namespace

TEST(Pyramid, LevelsHalveTheFineAxesAndKeepTheWorldPoints) {
  // A 1 x 1 x 3.5 grid keeps its slices until the other axes' spacing passes theirs.
  const std::array<int, 3> dims{130, 70, 40};
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->preScale(openvdb::Vec3d(1.0, 1.0, 3.5));
  xform->postRotate(0.3, openvdb::math::Y_AXIS);
  xform->postTranslate(openvdb::Vec3d(-4, 2, 7));
  const Volume vol = pyr_volume(dims, std::vector<float>(130 * 70 * 40, 1.0f), xform);
  const Pyramid p(vol);
  ASSERT_GE(p.levels(), 4);
  EXPECT_EQ(p.level(1).factor, openvdb::Coord(2, 2, 1));
  EXPECT_EQ(p.level(2).factor, openvdb::Coord(4, 4, 1));
  EXPECT_EQ(p.level(3).factor, openvdb::Coord(8, 8, 2));  // 7 <= 8: z halves at level 3
  // y stops where the next level would keep under kPyramidMinSamples samples: 70 -> 35 -> 17 ->
  // 8 -> (4).
  EXPECT_EQ(p.level(3).frame.hi[1] - p.level(3).frame.lo[1] + 1, 9);
  for (int k = 4; k < p.levels(); ++k) EXPECT_EQ(p.level(k).factor[1], 8) << k;
  for (int k = 0; k < p.levels(); ++k) {
    const PyramidLevel& l = p.level(k);
    // Level index j is level-0 index j * factor: the same world point.
    const openvdb::Vec3d j(3, -2, 5);
    const openvdb::Vec3d j0(j[0] * l.factor[0], j[1] * l.factor[1], j[2] * l.factor[2]);
    EXPECT_LT((l.frame.to_world(j) - p.level(0).frame.to_world(j0)).length(), 1e-9) << k;
    EXPECT_LT((l.grid->indexToWorld(j) - l.frame.to_world(j)).length(), 1e-9) << k;
    for (int a = 0; a < 3; ++a)
      EXPECT_NEAR(l.frame.spacing[a], p.level(0).frame.spacing[a] * l.factor[a], 1e-12);
  }
  // The samples' own smoothing: (v + 4) / 4 at each halving, in the level's units.
  EXPECT_DOUBLE_EQ(p.level(1).variance[0], 1.0);
  EXPECT_DOUBLE_EQ(p.level(2).variance[0], 1.25);
  EXPECT_DOUBLE_EQ(p.level(2).variance[2], 0.0);
  EXPECT_DOUBLE_EQ(p.level(3).variance[2], 1.0);
  // The level a scale reads: at least kPyramidVoxels of the level's spacing on its halved axes.
  EXPECT_EQ(p.level_for(3.9), 0);
  EXPECT_EQ(p.level_for(4.0), 1);
  EXPECT_EQ(p.level_for(7.9), 1);
  EXPECT_EQ(p.level_for(8.0), 2);
  EXPECT_EQ(p.level_for(16.0), 3);
  EXPECT_DOUBLE_EQ(p.upper_scale(0), 4.0);
  EXPECT_DOUBLE_EQ(p.upper_scale(2), 16.0);
}

TEST(Pyramid, SamplesFollowTheDefinitionWhateverBricksAreAsked) {
  const std::array<int, 3> dims{45, 38, 33};
  const std::vector<float> data = pyr_random(dims, 5);
  const Volume vol = pyr_volume(dims, data, openvdb::math::Transform::createLinearTransform(0.7));
  PyrDense d0;
  d0.lo = openvdb::Coord(0, 0, 0), d0.hi = openvdb::Coord(44, 37, 32);
  d0.v.assign(data.begin(), data.end());
  Pyramid whole(vol), parts(vol);
  ASSERT_GE(whole.levels(), 3);
  const PyrDense d1 = pyr_next_level(d0, whole.level(1).decimated);
  const PyrDense d2 = pyr_next_level(d1, whole.level(2).decimated);
  // Level 2 built in one call (level 1 built for it on the way), then in pieces in another
  // pyramid: the same values.
  whole.build(2, pyr_all_bricks(whole.level(2)));
  std::vector<openvdb::Coord> bricks = pyr_all_bricks(parts.level(2));
  std::reverse(bricks.begin(), bricks.end());
  for (const openvdb::Coord& b : bricks) parts.build(2, {b, b});
  parts.build(1, pyr_all_bricks(parts.level(1)));
  for (int k : {1, 2}) {
    const PyrDense& d = k == 1 ? d1 : d2;
    const PyramidLevel& l = whole.level(k);
    EXPECT_EQ(l.frame.lo, d.lo);
    EXPECT_EQ(l.frame.hi, d.hi);
    auto a = l.grid->getConstAccessor();
    auto b = parts.level(k).grid->getConstAccessor();
    double worst = 0;
    for (int z = d.lo[2]; z <= d.hi[2]; ++z)
      for (int y = d.lo[1]; y <= d.hi[1]; ++y)
        for (int x = d.lo[0]; x <= d.hi[0]; ++x) {
          const openvdb::Coord c(x, y, z);
          ASSERT_TRUE(a.isValueOn(c)) << k << " " << c;
          worst = std::max(worst, std::abs(a.getValue(c) - d.at(c)));
          ASSERT_EQ(a.getValue(c), b.getValue(c)) << k << " " << c;
        }
    EXPECT_LT(worst, 2e-6) << "level " << k;
  }
  EXPECT_GT(whole.built_bricks(), 0u);
}

TEST(Pyramid, SparseGridReadsItsBackgroundAtEveryLevel) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(2.0f);
  auto acc = grid->getAccessor();
  for (int z = -20; z < 20; ++z)
    for (int y = -20; y < 20; ++y)
      for (int x = -20; x < 20; ++x)
        if (x * x + y * y + z * z < 15 * 15) acc.setValue({x, y, z}, 5.0f);
  Volume vol;
  vol.grid = grid;
  vol.dense = false;
  vol.domain = grid->evalActiveVoxelBoundingBox();
  Pyramid p(vol);
  ASSERT_GE(p.levels(), 2);
  p.build(1, {{-2, -2, -2}, {0, 0, 0}, {4, 4, 4}});
  auto a = p.level(1).grid->getConstAccessor();
  EXPECT_NEAR(a.getValue({0, 0, 0}), 5.0, 1e-5);     // deep inside
  EXPECT_NEAR(a.getValue({36, 36, 36}), 2.0, 1e-6);  // far outside: the background
  const float edge = a.getValue({7, 0, 0});           // level-0 x = 14: the ball's edge
  EXPECT_GT(edge, 2.0f);
  EXPECT_LT(edge, 5.0f);
}

// A cubic field's reconstruction at a coarse level: the decimations, the level's prefilter and
// the B-spline together smooth each axis by sigma^2, which on a cubic is Gaussian smoothing
// exactly (only second moments act).
TEST(Pyramid, CubicFieldGivesTheGaussianSmoothedCubicAtEveryLevel) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const openvdb::Vec3d centre(60, 66, 58);
  const double c = uni(rng);
  double g[3], H[3][3], T[3][3][3];
  for (double& v : g) v = uni(rng);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) H[i][j] = H[j][i] = 0.02 * uni(rng);
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      for (int k = j; k < 3; ++k) {
        const double t = 0.0005 * uni(rng);
        T[i][j][k] = T[i][k][j] = T[j][i][k] = T[j][k][i] = T[k][i][j] = T[k][j][i] = t;
      }
  auto p = [&](const openvdb::Vec3d& w) {
    const openvdb::Vec3d x = w - centre;
    double v = c;
    for (int i = 0; i < 3; ++i) {
      v += g[i] * x[i];
      for (int j = 0; j < 3; ++j) {
        v += H[i][j] * x[i] * x[j] / 2;
        for (int k = 0; k < 3; ++k) v += T[i][j][k] * x[i] * x[j] * x[k] / 6;
      }
    }
    return v;
  };
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->postRotate(0.4, openvdb::math::Z_AXIS);
  xform->postRotate(0.3, openvdb::math::X_AXIS);
  xform->postTranslate(openvdb::Vec3d(5, 9, 14));
  const std::array<int, 3> dims{128, 128, 128};
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::size_t n = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        data[n++] = float(p(xform->indexToWorld(openvdb::Vec3d(x, y, z))));
  const Volume vol = pyr_volume(dims, data, xform);
  Pyramid pyramid(vol);
  for (double sigma : {2.2, 5.0, 9.0}) {
    const int k = pyramid.level_for(sigma);
    EXPECT_EQ(k, sigma < 4 ? 0 : sigma < 8 ? 1 : 2);
    const PyramidLevel& level = pyramid.level(k);
    Positions points;
    std::vector<openvdb::Vec3d> world;
    for (int i = 0; i < 4; ++i) {
      const openvdb::Vec3d idx(62 + 4 * uni(rng), 62 + 4 * uni(rng), 62 + 4 * uni(rng));
      world.push_back(xform->indexToWorld(idx));
      points.push_back({float(world.back()[0]), float(world.back()[1]), float(world.back()[2])});
    }
    const SmoothingPlan plan = plan_smoothing(level.frame, points, openvdb::Vec3d(0, 0, 0), sigma,
                                              level.variance);
    pyramid.build(k, plan.stages[0].bricks);
    const SmoothedSamples s = smooth_reference(*level.grid, plan);
    double trace = 0, lap_grad[3] = {0, 0, 0};
    for (int q = 0; q < 3; ++q) {
      trace += H[q][q];
      for (int m = 0; m < 3; ++m) lap_grad[m] += T[q][q][m];
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      const openvdb::Vec3d w(points[i][0], points[i][1], points[i][2]);
      const Jet jet = spline_jet(s, w, 3);
      const openvdb::Vec3d x = w - centre;
      double lap = trace;
      for (int m = 0; m < 3; ++m) lap += lap_grad[m] * x[m];
      EXPECT_NEAR(jet.value, p(w) + sigma * sigma / 2 * lap, 2e-4) << sigma;
      for (int q = 0; q < 3; ++q) {
        double grad = g[q] + sigma * sigma / 2 * lap_grad[q];
        for (int j = 0; j < 3; ++j) {
          grad += H[q][j] * x[j];
          for (int m = 0; m < 3; ++m) grad += T[q][j][m] * x[j] * x[m] / 2;
        }
        EXPECT_NEAR(jet.gradient[q], grad, 2e-5) << sigma << " d/dx" << q;
      }
      static const int kPairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
      for (int e = 0; e < 6; ++e) {
        const int q = kPairs[e][0], l = kPairs[e][1];
        double h = H[q][l];
        for (int m = 0; m < 3; ++m) h += T[q][l][m] * x[m];
        EXPECT_NEAR(jet.hessian[e], h, 2e-6) << sigma << " pair " << e;
      }
    }
  }
}

TEST(Pyramid, SupportGrowsWithTheScale) {
  const std::array<int, 3> dims{200, 200, 200};
  const Volume vol = pyr_volume(dims, std::vector<float>(200 * 200 * 200, 0.0f),
                                  openvdb::math::Transform::createLinearTransform(1.0));
  const Pyramid p(vol);
  double last = 0;
  for (double sigma = 0.7; sigma < 40; sigma *= 1.1) {
    const double s = pyramid_support(p, sigma, 2, 0.5);
    EXPECT_GE(s, last) << sigma;
    EXPECT_GE(s, 3 * sigma) << sigma;  // at least the prefilter's own reach
    last = s;
  }
}
