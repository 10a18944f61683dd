// Small 3-vector arithmetic (core/vec3.h).
#include "core/vec3.h"

#include <gtest/gtest.h>

#include <limits>

namespace isocurv {
namespace {

using namespace vec3;

TEST(Vec3, CrossIsRightHandedAndOrthogonal) {
  EXPECT_EQ(cross(Vec3d{1, 0, 0}, Vec3d{0, 1, 0}), (Vec3d{0, 0, 1}));
  EXPECT_EQ(cross(Vec3d{0, 1, 0}, Vec3d{0, 0, 1}), (Vec3d{1, 0, 0}));
  const Vec3d a{0.3, -1.7, 2.2}, b{4.1, 0.5, -0.9};
  const Vec3d c = cross(a, b);
  EXPECT_NEAR(dot(c, a), 0, 1e-12);
  EXPECT_NEAR(dot(c, b), 0, 1e-12);
  EXPECT_EQ(cross(b, a), scale(c, -1.0));
}

TEST(Vec3, ArithmeticComponentByComponent) {
  const Vec3d a{1, 2, 3}, b{-4, 0.5, 8};
  EXPECT_EQ(add(a, b), (Vec3d{-3, 2.5, 11}));
  EXPECT_EQ(sub(a, b), (Vec3d{5, 1.5, -5}));
  EXPECT_EQ(scale(a, 2.0), (Vec3d{2, 4, 6}));
  EXPECT_EQ(dot(a, b), -4 + 1 + 24);
  EXPECT_EQ(norm(Vec3d{3, 4, 12}), 13);
  EXPECT_EQ(to_double(Vec3f{0.1f, 2, 3}), (Vec3d{double(0.1f), 2, 3}));
  EXPECT_EQ(dot(Vec3f{1, 2, 3}, Vec3f{1, 1, 1}), 6.0f);  // float stays float
}

TEST(Vec3, NormalizedKeepsZeroAndNaNAndDividesOtherwise) {
  EXPECT_EQ(normalized(Vec3d{0, 3, 4}), (Vec3d{0, 0.6, 0.8}));
  EXPECT_EQ(normalized(Vec3d{0, 0, 0}), (Vec3d{0, 0, 0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(normalized(Vec3d{nan, 1, 1})[0]));
}

}  // namespace
}  // namespace isocurv
