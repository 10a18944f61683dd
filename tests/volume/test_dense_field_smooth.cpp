// volume::DenseField::smooth: the separable Gaussian the ray caster's --smooth applies before a
// cast. Linear fields are kept (a symmetric filter), a step gets exactly the variance asked for,
// non-finite samples neither spread nor vanish, and the bricks are ranked again.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "tests/mc/volumes.h"
#include "volume/dense_field.h"

namespace isocurv::test {
namespace {

float at(const volume::DenseField& f, int i, int j, int k) {
  return f.values[std::size_t(i) + std::size_t(f.nx) * (j + std::size_t(f.ny) * k)];
}

TEST(DenseFieldSmooth, KeepsLinearFieldsAwayFromTheFaces) {
  volume::DenseField f(
      sampled([](double x, double y, double z) { return float(x + 2 * y - z); }, {24, 20, 18}));
  const std::uint64_t id = f.id;
  f.smooth(2.0);
  EXPECT_NE(f.id, id);
  for (int k = 7; k < 11; ++k)  // 3 deviations from every face
    for (int j = 7; j < 13; ++j)
      for (int i = 7; i < 17; ++i) EXPECT_NEAR(at(f, i, j, k), i + 2 * j - k, 1e-4);
}

TEST(DenseFieldSmooth, AStepGetsTheVarianceAskedFor) {
  // A step along x: after smoothing, the differences along x are the filter's weights, whose
  // variance is sigma^2 exactly (prefilter_taps); y and z see a constant and leave it alone.
  volume::DenseField f(
      sampled([](double x, double, double) { return x < 15.5 ? 0.f : 1.f; }, {32, 8, 8}));
  const double sigma = 1.7;
  f.smooth(sigma);
  double sum = 0, mean = 0, var = 0;
  for (int i = 1; i < 32; ++i) {
    const double w = at(f, i, 4, 4) - at(f, i - 1, 4, 4);
    sum += w, mean += w * (i - 0.5);
  }
  mean /= sum;
  for (int i = 1; i < 32; ++i) {
    const double w = at(f, i, 4, 4) - at(f, i - 1, 4, 4);
    var += w * (i - 0.5 - mean) * (i - 0.5 - mean);
  }
  EXPECT_NEAR(sum, 1.0, 1e-6);
  EXPECT_NEAR(mean, 15.5, 1e-6);  // between samples 15 and 16
  EXPECT_NEAR(var / sum, sigma * sigma, 1e-4);
  EXPECT_FLOAT_EQ(at(f, 10, 0, 0), at(f, 10, 7, 7));
}

TEST(DenseFieldSmooth, NonFiniteSamplesStayAndDoNotSpread) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  volume::DenseField f(
      sampled([](double x, double, double) { return float(x > 10); }, {20, 20, 20}));
  f.values[8 + 20 * (8 + 20 * 8)] = nan;  // a sample the loaders would read as NaN
  f.smooth(1.0);
  EXPECT_TRUE(std::isnan(at(f, 8, 8, 8)));
  for (int i = 5; i < 12; ++i) {
    if (i == 8) continue;
    EXPECT_TRUE(std::isfinite(at(f, i, 8, 8))) << i;
  }
  EXPECT_NEAR(at(f, 2, 8, 8), 0.0, 1e-6) << "far from the step and the NaN";
  // The bricks are ranked from the smoothed samples: the step's bricks hold values in (0, 1).
  std::array<int, 6> box{};
  ASSERT_TRUE(f.straddling_box(0.5f, box));
  EXPECT_LE(box[0], 8);
  EXPECT_GE(box[1], 16);
}

TEST(DenseFieldSmooth, RefusesBadWidths) {
  volume::DenseField f(sampled([](double x, double, double) { return float(x); }, {8, 8, 8}));
  EXPECT_THROW(f.smooth(-1), Error);
  EXPECT_THROW(f.smooth(volume::kMaxSmoothingVoxels + 0.5), Error);
  EXPECT_THROW(f.smooth(std::nan("")), Error);
  const std::vector<float> before = f.values;
  f.smooth(0);
  EXPECT_EQ(f.values, before);
}

}  // namespace
}  // namespace isocurv::test
