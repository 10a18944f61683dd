// lines::resolve_thresholds: the typical curvature m is the exact median of the finite
// max(|k1|, |k2|), as a sort would give it, whatever the values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "core/error.h"
#include "lines/options.h"

namespace isocurv::lines {
namespace {

// The median the way the definition reads: sort the finite maxima, take the middle one.
double sorted_median(const curvature::CurvatureField& f) {
  std::vector<float> m;
  for (std::size_t i = 0; i < f.k1.size(); ++i) {
    const float x = std::max(std::fabs(f.k1[i]), std::fabs(f.k2[i]));
    if (std::isfinite(x)) m.push_back(x);
  }
  if (m.empty()) return 0;
  std::sort(m.begin(), m.end());
  return m[m.size() / 2];
}

TEST(LinesThresholds, TypicalCurvatureIsTheExactMedian) {
  std::mt19937 rng(7);
  std::normal_distribution<float> wide(0, 3);
  std::uniform_int_distribution<int> pick(0, 19);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (std::size_t n : {1, 2, 3, 4, 7, 100, 1001, 65536, 200000}) {
    curvature::CurvatureField f;
    for (std::size_t i = 0; i < n; ++i) {
      float a = wide(rng) * std::exp(wide(rng)), b = wide(rng);
      switch (pick(rng)) {  // some non-finite values, ties, zeros and tiny values
        case 0:
          a = nan;
          break;
        case 1:
          b = -inf;
          break;
        case 2:
          a = 0.25f, b = -0.25f;
          break;
        case 3:
          a = -0.0f, b = 0;
          break;
        case 4:
          a = 1e-30f, b = -1e-38f;
          break;
        default:
          break;
      }
      f.k1.push_back(a), f.k2.push_back(b);
    }
    const Thresholds t = resolve_thresholds(f, Options{});
    EXPECT_EQ(t.typical_curvature, sorted_median(f)) << n << " vertices";
    EXPECT_DOUBLE_EQ(t.suggestive, 0.05 * t.typical_curvature * t.typical_curvature);
    EXPECT_DOUBLE_EQ(t.ridge, 1.5 * t.typical_curvature);
  }
}

TEST(LinesThresholds, NoFiniteValueGivesZero) {
  curvature::CurvatureField f;
  EXPECT_EQ(resolve_thresholds(f, Options{}).typical_curvature, 0);
  f.k1 = {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()};
  f.k2 = {0, 0};
  EXPECT_EQ(resolve_thresholds(f, Options{}).typical_curvature, 0);
}

TEST(LinesThresholds, BadOptionsAreErrors) {
  const curvature::CurvatureField f;
  Options o;
  o.suggestive_angle_deg = 90;
  EXPECT_THROW(resolve_thresholds(f, o), Error);
  o = Options{};
  o.ridge_threshold = -1;
  EXPECT_THROW(resolve_thresholds(f, o), Error);
  o = Options{};
  o.smoothing_steps = 101;
  EXPECT_THROW(resolve_thresholds(f, o), Error);
}

}  // namespace
}  // namespace isocurv::lines
