// datasets/animated.h: the animated fields' analytic derivatives and their exact curvature.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "datasets/animated.h"
#include "datasets/exact_curvature.h"

namespace isocurv::datasets {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

TEST(AnimatedFields, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  for (const std::string& name : animated_field_names())
    for (double t : {0.0, 0.13, 0.5, 0.77}) {
      const auto f = make_animated_field(name, t);
      EXPECT_EQ(f->name(), name);
      for (int s = 0; s < 20; ++s) {
        const Vector3d p(u(rng), u(rng), u(rng));
        const double h = 1e-5;
        Vector3d g;
        Matrix3d hs;
        for (int a = 0; a < 3; ++a) {
          const Vector3d e = Vector3d::Unit(a) * h;
          g[a] = (f->value(p + e) - f->value(p - e)) / (2 * h);
          hs.col(a) = (f->gradient(p + e) - f->gradient(p - e)) / (2 * h);
        }
        const double gs = std::max(1.0, f->gradient(p).norm());
        EXPECT_LT((g - f->gradient(p)).norm(), 1e-5 * gs) << name << " t=" << t;
        EXPECT_LT((hs - f->hessian(p)).norm(), 1e-4 * std::max(1.0, f->hessian(p).norm()))
            << name << " t=" << t;
      }
    }
}

TEST(AnimatedFields, PulsingSphereHasItsRadiusEveryFrame) {
  for (int i = 0; i < 16; ++i) {
    const double t = i / 16.0, r = pulsing_sphere_radius(t);
    EXPECT_NEAR(r, 0.6 + 0.2 * std::sin(2 * 3.14159265358979323846 * t), 1e-15);
    const auto f = make_animated_field("pulsing_sphere", t);
    const Vector3d p = project_to_surface(*f, Vector3d(0.3, -0.2, 0.5));
    EXPECT_NEAR(p.norm(), r, 1e-12);
    const SurfaceCurvature c = exact_curvature(*f, p);
    EXPECT_NEAR(c.H, 1 / r, 1e-9);
    EXPECT_NEAR(c.K, 1 / (r * r), 1e-9);
  }
}

TEST(AnimatedFields, GyroidPhaseIsTheGyroidMovedAlongX) {
  const auto f0 = make_animated_field("gyroid_phase", 0.0);
  const auto f = make_animated_field("gyroid_phase", 0.25);
  for (double x : {-0.4, 0.1, 0.33})
    EXPECT_NEAR(f->value(Vector3d(x, 0.2, -0.7)), f0->value(Vector3d(x + 0.25, 0.2, -0.7)), 1e-12);
  // Periodic in t.
  const auto f1 = make_animated_field("gyroid_phase", 1.0);
  EXPECT_NEAR(f1->value(Vector3d(0.1, 0.2, 0.3)), f0->value(Vector3d(0.1, 0.2, 0.3)), 1e-12);
}

TEST(AnimatedFields, MetaballsMoveAndStayInTheBox) {
  const auto a = make_animated_field("metaballs", 0.0), b = make_animated_field("metaballs", 0.3);
  const Vector3d p(0.1, 0.1, 0.1);
  EXPECT_NE(a->value(p), b->value(p)) << "the sites move";
  // The surface (value 0.5) never reaches the box: on its faces the field is below 0.5.
  for (double t = 0; t < 1; t += 0.05) {
    const auto f = make_animated_field("metaballs", t);
    for (double y = -1; y <= 1; y += 0.25)
      for (double z = -1; z <= 1; z += 0.25) {
        EXPECT_LT(f->value(Vector3d(1, y, z)), 0.5);
        EXPECT_LT(f->value(Vector3d(z, y, -1)), 0.5);
      }
  }
}

TEST(AnimatedFields, UnknownNameAndBadTimeAreErrors) {
  EXPECT_THROW(make_animated_field("nope", 0), std::exception);
  EXPECT_THROW(make_animated_field("metaballs", std::nan("")), std::exception);
}

}  // namespace
}  // namespace isocurv::datasets
