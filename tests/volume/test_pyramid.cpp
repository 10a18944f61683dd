// The scale-space pyramid (volume/pyramid.h): its levels' frames and decimated axes, each level's
// samples against the definition (the finer level smoothed and sampled at every second index,
// clamped to the domain) computed densely, values that do not depend on which bricks were asked
// for, the level an evaluation reads, and the whole reconstruction at a coarse level on a cubic
// field, where it must equal Gaussian smoothing exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "cubic_field.h"
#include "volume/from_dense.h"
#include "volume/prefilter.h"
#include "volume/pyramid.h"
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

// A dense box of samples in double, x fastest: level 0's domain (read clamped, as the pyramid
// reads a dense volume) or a coarser level's samples over a box past the domain (read as they
// are: the coarser levels smooth level 0's extension).
struct PyrDense {
  openvdb::Coord lo, hi;
  bool clamp = false;
  std::vector<double> v;
  int n(int a) const { return hi[a] - lo[a] + 1; }
  double at(openvdb::Coord c) const {
    for (int a = 0; a < 3; ++a) {
      if (clamp) c[a] = std::clamp(c[a], lo[a], hi[a]);
      EXPECT_TRUE(c[a] >= lo[a] && c[a] <= hi[a]) << c;
    }
    return v[(std::size_t(c[2] - lo[2]) * n(1) + (c[1] - lo[1])) * n(0) + (c[0] - lo[0])];
  }
};

// The definition: level k + 1 from level k, every sample of `box` (within what `d` holds).
PyrDense pyr_next_level(const PyrDense& d, const std::array<bool, 3>& decimated,
                        const openvdb::CoordBBox& box) {
  const PrefilterTaps t = prefilter_taps(kPyramidVariance);
  PyrDense out;
  out.lo = box.min(), out.hi = box.max();
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
  // y stops where the next level would keep under kPyramidMinSamples samples inside the box:
  // 70 -> 35 -> 17 -> 8 -> (4).
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
  d0.clamp = true;
  d0.v.assign(data.begin(), data.end());
  Pyramid whole(vol), parts(vol);
  ASSERT_GE(whole.levels(), 3);
  // Level 2's first brick and the level-1 samples it reads (past the box).
  const openvdb::CoordBBox box2(openvdb::Coord(0, 0, 0), openvdb::Coord(7, 7, 7));
  const int r = prefilter_taps(kPyramidVariance).radius;
  const openvdb::CoordBBox box1(openvdb::Coord(-r, -r, -r), openvdb::Coord(14 + r, 14 + r, 14 + r));
  const PyrDense d1 = pyr_next_level(d0, whole.level(1).decimated, box1);
  const PyrDense d2 = pyr_next_level(d1, whole.level(2).decimated, box2);
  // Level 2 built in one call (level 1 built for it on the way), then in pieces in another
  // pyramid: the same values.
  whole.build(
      2, {{0, 0, 0}, {1, 1, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {1, 1, 0}, {0, 1, 1}, {1, 0, 1}});
  for (const openvdb::Coord& b : pyr_all_bricks(whole.level(1))) whole.build(1, {b});
  whole.build(1, {{-1, -1, -1}, {3, 3, 3}});
  std::vector<openvdb::Coord> bricks = {{1, 1, 1}, {0, 0, 0}, {1, 0, 1}, {0, 1, 1},
                                        {1, 1, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
  for (const openvdb::Coord& b : bricks) parts.build(2, {b, b});
  parts.build(1, {{3, 3, 3}, {-1, -1, -1}});
  parts.build(1, pyr_all_bricks(parts.level(1)));
  for (int k : {1, 2}) {
    const PyrDense& d = k == 1 ? d1 : d2;
    const PyramidLevel& l = whole.level(k);
    EXPECT_TRUE(l.frame.clamp);
    // The box reaches the first sample whose decimation taps all lie past the finer box.
    const openvdb::Coord lo = k == 1 ? openvdb::Coord(-4, -4, -4) : openvdb::Coord(-6, -6, -6);
    const openvdb::Coord hi = k == 1 ? openvdb::Coord(26, 23, 20) : openvdb::Coord(17, 16, 14);
    EXPECT_EQ(l.frame.lo, lo);
    EXPECT_EQ(l.frame.hi, hi);
    auto a = l.grid->getConstAccessor();
    auto b = parts.level(k).grid->getConstAccessor();
    double worst = 0;
    // Level 2's brick (0, 0, 0); level 1's samples it reads, past the box too.
    const openvdb::CoordBBox check = k == 1 ? box1 : box2;
    for (int z = check.min()[2]; z <= check.max()[2]; ++z)
      for (int y = check.min()[1]; y <= check.max()[1]; ++y)
        for (int x = check.min()[0]; x <= check.max()[0]; ++x) {
          const openvdb::Coord c(x, y, z);
          // A read clamps to the level's box; the definition does not (it is constant there).
          openvdb::Coord in = c;
          for (int q = 0; q < 3; ++q) in[q] = std::clamp(in[q], lo[q], hi[q]);
          ASSERT_TRUE(a.isValueOn(in)) << k << " " << c;
          worst = std::max(worst, std::abs(a.getValue(in) - d.at(c)));
          ASSERT_EQ(a.getValue(in), b.getValue(in)) << k << " " << c;
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
  const float edge = a.getValue({7, 0, 0});          // level-0 x = 14: the ball's edge
  EXPECT_GT(edge, 2.0f);
  EXPECT_LT(edge, 5.0f);
}

// A cubic field's reconstruction at a coarse level: the decimations, the level's prefilter and
// the B-spline together smooth each axis by sigma^2, which on a cubic is Gaussian smoothing
// exactly (only second moments act).
TEST(Pyramid, CubicFieldGivesTheGaussianSmoothedCubicAtEveryLevel) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const test::RandomCubic p(rng, uni, openvdb::Vec3d(60, 66, 58), 0.02, 0.0005);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(1.0);
  xform->postRotate(0.4, openvdb::math::Z_AXIS);
  xform->postRotate(0.3, openvdb::math::X_AXIS);
  xform->postTranslate(openvdb::Vec3d(5, 9, 14));
  const std::array<int, 3> dims{128, 128, 128};
  const Volume vol = pyr_volume(dims, p.sample(*xform, dims), xform);
  Pyramid pyramid(vol);
  for (double sigma : {2.2, 5.0, 9.0}) {
    const int k = pyramid.level_for(sigma);
    EXPECT_EQ(k, sigma < 4 ? 0 : sigma < 8 ? 1 : 2);
    const PyramidLevel& level = pyramid.level(k);
    Positions points;
    for (int i = 0; i < 4; ++i) {
      const openvdb::Vec3d w = xform->indexToWorld(
          openvdb::Vec3d(62 + 4 * uni(rng), 62 + 4 * uni(rng), 62 + 4 * uni(rng)));
      points.push_back({float(w[0]), float(w[1]), float(w[2])});
    }
    const SmoothingPlan plan =
        plan_smoothing(level.frame, points, openvdb::Vec3d(0, 0, 0), sigma, level.variance);
    pyramid.build(k, plan.stages[0].bricks);
    const SmoothedSamples s = smooth_reference(*level.grid, plan);
    for (const Vec3f& q : points) {
      const openvdb::Vec3d w(q[0], q[1], q[2]);
      test::expect_jet_near(spline_jet(s, w, 3), p.smoothed(w, sigma), {2e-4, 2e-5, 2e-6, 1e-6},
                            "sigma " + std::to_string(sigma));
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

// A blurred, noisy, quantised ball: the same scale read from level 0 and from the coarser level
// that serves it gives H as close to 1 / R (the level set through each point of a Gaussian-
// smoothed ball is a sphere of its own radius).
TEST(Pyramid, CoarseLevelAgreesWithLevelZeroOnABlurredBall) {
  const std::array<int, 3> dims{96, 96, 96};
  std::vector<float> data(std::size_t(96) * 96 * 96);
  std::size_t n = 0;
  std::mt19937 noise_rng(9);
  std::normal_distribution<double> noise(0.0, 3.0);
  for (int z = 0; z < 96; ++z)
    for (int y = 0; y < 96; ++y)
      for (int x = 0; x < 96; ++x) {
        const double r =
            std::sqrt((x - 47.3) * (x - 47.3) + (y - 48.1) * (y - 48.1) + (z - 47.7) * (z - 47.7));
        data[n++] = float(std::round(100.0 * 0.5 * std::erfc((r - 30.0) / (std::sqrt(2.0) * 1.2)) +
                                     noise(noise_rng)));
      }
  const Volume vol = pyr_volume(dims, data, openvdb::math::Transform::createLinearTransform(1.0));
  Pyramid pyramid(vol);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Positions points;
  for (int i = 0; i < 200; ++i) {
    openvdb::Vec3d d(uni(rng), uni(rng), uni(rng));
    d.normalize();
    const openvdb::Vec3d p = openvdb::Vec3d(47.3, 48.1, 47.7) + 30.0 * d;
    points.push_back({float(p[0]), float(p[1]), float(p[2])});
  }
  for (double sigma : {5.0, 7.0, 10.0}) {
    auto mean_curvature = [&](int k) {
      const PyramidLevel& level = pyramid.level(k);
      const SmoothingPlan plan =
          plan_smoothing(level.frame, points, openvdb::Vec3d(0, 0, 0), sigma, level.variance);
      pyramid.build(k, plan.stages[0].bricks);
      const SmoothedSamples s = smooth_reference(*level.grid, plan);
      std::vector<double> H;
      for (const Vec3f& p : points) {
        const Jet j = spline_jet(s, openvdb::Vec3d(p[0], p[1], p[2]), 3);
        const openvdb::Vec3d g(j.gradient[0], j.gradient[1], j.gradient[2]);
        const double len = g.length();
        // H = (|g|^2 tr(Hs) - g'Hs g) / (2 |g|^3), sign flipped for a density (inside above).
        const double* h = j.hessian.data();
        const double tr = h[0] + h[3] + h[5];
        const double gHg = g[0] * (h[0] * g[0] + h[1] * g[1] + h[2] * g[2]) +
                           g[1] * (h[1] * g[0] + h[3] * g[1] + h[4] * g[2]) +
                           g[2] * (h[2] * g[0] + h[4] * g[1] + h[5] * g[2]);
        H.push_back(-(len * len * tr - gHg) / (2 * len * len * len));
      }
      return H;
    };
    const std::vector<double> H0 = mean_curvature(0), Hk = mean_curvature(pyramid.level_for(sigma));
    double e0 = 0, ek = 0, m0 = 0, mk = 0;
    for (std::size_t i = 0; i < H0.size(); ++i) {
      e0 = std::max(e0, std::abs(H0[i] * 30.0 - 1));
      ek = std::max(ek, std::abs(Hk[i] * 30.0 - 1));
      m0 += H0[i] * 30.0 - 1, mk += Hk[i] * 30.0 - 1;
    }
    // Noise (deviation 3 on a step of 100) and 8-bit rounding dominate both (worst 0.3-1.4% of
    // 1 / R here); the coarse level adds no error of its own.
    EXPECT_LT(ek, 1.25 * e0) << sigma;
    EXPECT_LT(std::abs(mk - m0) / double(H0.size()), 5e-4) << sigma;
  }
}

// A side too thin to halve bounds the scales: 16 samples of it (kMaxPrefilterDeviation), however
// large the other sides; the thick sides halve on.
TEST(Pyramid, ThinSideBoundsTheLargestScale) {
  const std::array<int, 3> dims{200, 200, 10};
  const Volume vol = pyr_volume(dims, std::vector<float>(200 * 200 * 10, 0.0f),
                                openvdb::math::Transform::createLinearTransform(0.5));
  const Pyramid p(vol);
  ASSERT_GE(p.levels(), 4);
  for (int k = 1; k < p.levels(); ++k) EXPECT_EQ(p.level(k).factor[2], 1) << k;
  EXPECT_EQ(p.level(3).factor[0], 8);
  EXPECT_DOUBLE_EQ(p.max_scale(), kMaxPrefilterDeviation * 0.5);
}

// The pyramid kept between estimates on one volume: reused by the next lease of the same grid
// (its bricks built once), never by another grid's, and holding no reference to the grid in
// between (a volume it served can go).
TEST(PyramidLease, KeptForTheSameGridOnlyAndNeverKeepsItAlive) {
  const std::array<int, 3> dims{40, 36, 34};
  const std::vector<float> data = pyr_random(dims, 9);
  const Volume vol = pyr_volume(dims, data, openvdb::math::Transform::createLinearTransform(1.0));
  std::size_t built = 0;
  {
    PyramidLease first(vol);
    EXPECT_FALSE(first.reused());
    first->build(2, {{0, 0, 0}, {1, 1, 1}});
    built = first->built_bricks();
    ASSERT_GT(built, 0u);
  }
  EXPECT_EQ(vol.grid.use_count(), 1);  // the kept pyramid does not hold the grid
  {
    PyramidLease again(vol);
    EXPECT_TRUE(again.reused());
    EXPECT_EQ(again->built_bricks(), built);
    EXPECT_EQ(again->level(0).grid, vol.grid);  // level 0 reads the volume again
    // While it is leased, a second lease of the same volume gets a pyramid of its own.
    PyramidLease second(vol);
    EXPECT_FALSE(second.reused());
    EXPECT_EQ(second->built_bricks(), 0u);
  }
  // The same values in another grid (a copy): not the same volume, a new pyramid.
  Volume copy = vol;
  copy.grid = vol.grid->deepCopy();
  {
    PyramidLease other(copy);
    EXPECT_FALSE(other.reused());
  }
  {
    PyramidLease back(vol);  // the copy's lease replaced vol's kept pyramid
    EXPECT_FALSE(back.reused());
  }
  // A grid that is gone is never matched, even by a new grid at the same address.
  {
    Volume gone = pyr_volume(dims, data, openvdb::math::Transform::createLinearTransform(1.0));
    { PyramidLease l(gone); }
    gone.grid.reset();
    Volume fresh = pyr_volume(dims, data, openvdb::math::Transform::createLinearTransform(1.0));
    PyramidLease l(fresh);
    EXPECT_FALSE(l.reused());
  }
}
