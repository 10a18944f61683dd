// curvature::field_stats: area weights, percentiles, and unreliable vertices left out.
#include "curvature/field_stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace isocurv::curvature {
namespace {

CurvatureField field(const std::vector<float>& k, const std::vector<float>& area) {
  CurvatureField f;
  f.k1 = f.k2 = f.H = k;
  for (float x : k) f.K.push_back(x * x);
  f.area = area;
  return f;
}

TEST(FieldStats, AreaWeightedMeanAndPercentiles) {
  // Values 1, 2, 3 with areas 1, 1, 8: the area-weighted mean is 2.7 (the plain one 2), and the
  // median by area is 3.
  const FieldStats s = field_stats(field({2, 1, 3}, {1, 1, 8}), 0.1);
  EXPECT_TRUE(s.area_weighted);
  EXPECT_EQ(s.counted, 3u);
  EXPECT_DOUBLE_EQ(s.weight, 10);
  EXPECT_NEAR(s.H.mean, 2.7, 1e-12);
  EXPECT_EQ(s.H.min, 1);
  EXPECT_EQ(s.H.max, 3);
  ASSERT_EQ(kStatPercentiles[0], 1);
  EXPECT_EQ(s.H.percentiles[0], 1) << "p1: the first 10% of the area has value 1";
  EXPECT_EQ(s.H.percentiles[3], 3) << "p50";
  EXPECT_NEAR(s.K.mean, (4 + 1 + 72) / 10.0, 1e-12);
}

TEST(FieldStats, UnreliableVerticesAreCountedAndLeftOut) {
  // Mean edge 0.5: unreliable above 1 / 0.25 = 4. One vertex at -1024 (a sliver's spike) and one
  // NaN are left out of every statistic.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const FieldStats s = field_stats(field({1, -1024, 2, nan, 3}, {1, 100, 1, 1, 1}), 0.5);
  EXPECT_DOUBLE_EQ(s.unreliable_above, 4);
  EXPECT_EQ(s.unreliable, 1u);
  EXPECT_EQ(s.non_finite, 1u);
  EXPECT_EQ(s.counted, 3u);
  EXPECT_EQ(s.H.min, 1);
  EXPECT_NEAR(s.H.mean, 2, 1e-12);
  EXPECT_EQ(s.H.percentiles[0], 1);
  // The rule takes max(|k1|, |k2|): a large k2 alone makes a vertex unreliable.
  CurvatureField f = field({1, 1}, {1, 1});
  f.k2[1] = -5;
  EXPECT_EQ(field_stats(f, 0.5).unreliable, 1u);
  // Without an Area array every vertex weighs 1.
  const FieldStats u = field_stats(field({1, 2, 6}, {}), 0);
  EXPECT_FALSE(u.area_weighted);
  EXPECT_EQ(u.unreliable, 0u) << "no threshold without an edge length";
  EXPECT_NEAR(u.H.mean, 3, 1e-12);
  EXPECT_TRUE(field_stats(CurvatureField{}, 1).H.empty);
}

TEST(FieldStats, UnmeasuredVerticesAreCountedApartAndLeftOut) {
  // The volume estimator flags the vertices it could not measure Unreliable and gives them zero
  // curvature: counted as H = 0 they would drag the median of a convex surface to zero.
  CurvatureField f = field({0, 2, 0, 3, 4, 0}, {1, 1, 1, 1, 1, 1});
  f.unreliable = {1, 0, 1, 0, 0, 1};
  const FieldStats s = field_stats(f, 0.1);
  EXPECT_EQ(s.unmeasured, 3u);
  EXPECT_EQ(s.unreliable, 0u);
  EXPECT_EQ(s.counted, 3u);
  EXPECT_EQ(s.H.min, 2) << "no placeholder zero among the values";
  EXPECT_EQ(s.H.percentiles[3], 3) << "p50 of 2, 3, 4";
  EXPECT_NEAR(s.H.mean, 3, 1e-12);
  // A flagged vertex is unmeasured even where its placeholder is not finite or is huge.
  f.H[0] = std::numeric_limits<float>::quiet_NaN();
  f.k1[2] = 1e9f;
  const FieldStats t = field_stats(f, 0.1);
  EXPECT_EQ(t.unmeasured, 3u);
  EXPECT_EQ(t.non_finite + t.unreliable, 0u);
  // counted_vertices marks exactly the vertices the statistics use.
  f.k1[3] = 1e9f;  // measured, over the threshold
  const std::vector<std::uint8_t> c = counted_vertices(f, 0.1);
  EXPECT_EQ(c, (std::vector<std::uint8_t>{0, 1, 0, 0, 1, 0}));
  EXPECT_EQ(field_stats(f, 0.1).counted, 2u);
}

}  // namespace
}  // namespace isocurv::curvature

namespace isocurv::curvature {
namespace {

// The one rule (flag_implausible): what the statistics leave out is what the mesh flags. A strip
// of two triangles with edges 1, 1 and sqrt 2 (mean 1.138): threshold 1.757.
TEST(FieldStats, ImplausibleVerticesAreFlaggedInTheMeshAsTheStatisticsLeaveThemOut) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  CurvatureField f = field({0.5f, 3.0f, nan, -1.0f}, {1, 1, 1, 1});
  const double mean_edge = (4 + 2 * std::sqrt(2.0)) / 6;
  const FieldStats before = field_stats(f, mean_edge);
  EXPECT_EQ(before.unreliable + before.non_finite, 2u);
  EXPECT_EQ(flag_implausible(m, f), 2u);
  ASSERT_EQ(f.unreliable.size(), 4u);
  EXPECT_EQ(f.unreliable, (std::vector<std::uint8_t>{0, 1, 1, 0}));
  EXPECT_EQ(f.k1[1], 3.0f) << "values are kept as estimated";
  const FieldStats after = field_stats(f, mean_edge);
  EXPECT_EQ(after.unmeasured, 2u);
  EXPECT_EQ(after.unreliable + after.non_finite, 0u) << "nothing left out that is not flagged";
  EXPECT_EQ(after.counted, before.counted);
  EXPECT_EQ(flag_implausible(m, f), 0u) << "flagged once";
}

}  // namespace
}  // namespace isocurv::curvature
