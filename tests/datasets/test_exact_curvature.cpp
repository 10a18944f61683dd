// exact_curvature and project_to_surface against closed forms (sphere, torus, ellipsoid).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"

using namespace isocurv;
using namespace isocurv::datasets;
using Eigen::Vector3d;

namespace {

constexpr double kPi = 3.14159265358979323846;

Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// The same surface described by -F with the other inside side: curvature must not change.
class Flipped final : public Field {
 public:
  explicit Flipped(std::unique_ptr<Field> f) : Field(flip(f->info())), f_(std::move(f)) {}
  double value(const Vector3d& p) const override { return -f_->value(p); }
  Vector3d gradient(const Vector3d& p) const override { return -f_->gradient(p); }
  Eigen::Matrix3d hessian(const Vector3d& p) const override { return -f_->hessian(p); }

 private:
  static FieldInfo flip(FieldInfo i) {
    i.isovalue = -i.isovalue;
    i.inside = i.inside == volume::Inside::Above ? volume::Inside::Below : volume::Inside::Above;
    return i;
  }
  std::unique_ptr<Field> f_;
};

void expect_parallel(const Vector3d& a, const Vector3d& b, double tol) {
  EXPECT_NEAR(std::abs(a.normalized().dot(b.normalized())), 1.0, tol) << a.transpose() << " vs " << b.transpose();
}

void expect_frame(const SurfaceCurvature& c) {
  EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
  EXPECT_NEAR(c.dir1.norm(), 1.0, 1e-12);
  EXPECT_NEAR(c.dir2.norm(), 1.0, 1e-12);
  EXPECT_NEAR(c.dir1.dot(c.normal), 0.0, 1e-12);
  EXPECT_NEAR(c.dir1.cross(c.dir2).dot(c.normal), 1.0, 1e-12);  // right-handed
  EXPECT_GE(c.k1, c.k2);
  EXPECT_DOUBLE_EQ(c.H, 0.5 * (c.k1 + c.k2));
  EXPECT_DOUBLE_EQ(c.K, c.k1 * c.k2);
}

}  // namespace

TEST(ExactCurvature, SolidSphereIsPlusOneOverRForBothVolumeKinds) {
  const double R = 0.8;
  std::mt19937 rng(1);
  auto sphere = make_field("sphere");
  ASSERT_EQ(sphere->inside(), volume::Inside::Below);
  Flipped density(make_field("sphere"));  // R - |p|, inside above
  for (int i = 0; i < 200; ++i) {
    const Vector3d u = random_unit(rng);
    for (const Field* f : {static_cast<const Field*>(sphere.get()), static_cast<const Field*>(&density)}) {
      const SurfaceCurvature c = exact_curvature(*f, R * u);
      expect_frame(c);
      EXPECT_NEAR(c.k1, 1 / R, 1e-12);
      EXPECT_NEAR(c.k2, 1 / R, 1e-12);
      EXPECT_NEAR(c.H, 1 / R, 1e-12);
      EXPECT_NEAR(c.K, 1 / (R * R), 1e-12);
      EXPECT_NEAR((c.normal - u).norm(), 0.0, 1e-12);
    }
  }
}

TEST(ExactCurvature, TorusClosedForms) {
  const double R = 0.6, r = 0.25;
  auto torus = make_field("torus");
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  int negative_K = 0;
  for (int i = 0; i < 500; ++i) {
    const double u = angle(rng), v = angle(rng);
    const Vector3d p((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    const Vector3d normal(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
    const Vector3d meridian(-std::sin(v) * std::cos(u), -std::sin(v) * std::sin(u), std::cos(v));
    const Vector3d parallel(-std::sin(u), std::cos(u), 0);
    ASSERT_NEAR(torus->value(p), 0.0, 1e-14);
    const SurfaceCurvature c = exact_curvature(*torus, p);
    expect_frame(c);
    const double k_tube = 1 / r, k_ring = std::cos(v) / (R + r * std::cos(v));
    EXPECT_NEAR((c.normal - normal).norm(), 0.0, 1e-12);
    EXPECT_NEAR(c.k1, k_tube, 1e-11);
    EXPECT_NEAR(c.k2, k_ring, 1e-11);
    EXPECT_NEAR(c.K, k_tube * k_ring, 1e-10);
    EXPECT_NEAR(c.H, 0.5 * (k_tube + k_ring), 1e-11);
    expect_parallel(c.dir1, meridian, 1e-12);
    expect_parallel(c.dir2, parallel, 1e-12);
    negative_K += c.K < 0;
  }
  EXPECT_GT(negative_K, 100);  // the inner half is saddle-shaped
  // Outer and inner equator: +1/(R+r) and -1/(R-r).
  EXPECT_NEAR(exact_curvature(*torus, Vector3d(R + r, 0, 0)).k2, 1 / (R + r), 1e-12);
  EXPECT_NEAR(exact_curvature(*torus, Vector3d(0, R - r, 0)).k2, -1 / (R - r), 1e-12);
  // Inverting the field and the inside side describes the same solid torus.
  Flipped flipped(make_field("torus"));
  const SurfaceCurvature a = exact_curvature(*torus, Vector3d(0, R - r, 0)),
                         b = exact_curvature(flipped, Vector3d(0, R - r, 0));
  EXPECT_NEAR(a.k1, b.k1, 1e-12);
  EXPECT_NEAR(a.k2, b.k2, 1e-12);
  EXPECT_NEAR((a.normal - b.normal).norm(), 0.0, 1e-12);
}

TEST(ExactCurvature, EllipsoidGaussianAndMeanCurvature) {
  const double a = 0.8, b = 0.6, c = 0.4;
  auto ell = make_field("ellipsoid");
  std::mt19937 rng(3);
  for (int i = 0; i < 500; ++i) {
    const Vector3d s = random_unit(rng);
    const Vector3d p(a * s.x(), b * s.y(), c * s.z());
    const SurfaceCurvature k = exact_curvature(*ell, p);
    expect_frame(k);
    const double h2 = std::pow(p.x() / (a * a), 2) + std::pow(p.y() / (b * b), 2) + std::pow(p.z() / (c * c), 2);
    const double K = 1 / (a * a * b * b * c * c * h2 * h2);
    const double H = (a * a + b * b + c * c - p.squaredNorm()) / (2 * a * a * b * b * c * c * std::pow(h2, 1.5));
    EXPECT_NEAR(k.K, K, 1e-10 * K);
    EXPECT_NEAR(k.H, H, 1e-10 * H);
    EXPECT_GT(k.k2, 0);
    EXPECT_GT(k.normal.dot(p), 0);  // outward
  }
  // At the tip of the longest axis both curvatures are a / b^2 and a / c^2.
  const SurfaceCurvature tip = exact_curvature(*ell, Vector3d(a, 0, 0));
  EXPECT_NEAR(tip.k1, a / (c * c), 1e-12);
  EXPECT_NEAR(tip.k2, a / (b * b), 1e-12);
  expect_parallel(tip.dir1, Vector3d::UnitZ(), 1e-12);
}

TEST(ExactCurvature, ProjectionLandsOnTheSurface) {
  std::mt19937 rng(4);
  for (const auto& name : field_names()) {
    auto f = make_field(name);
    std::uniform_real_distribution<double> ux(f->box().min().x(), f->box().max().x()),
        uy(f->box().min().y(), f->box().max().y()), uz(f->box().min().z(), f->box().max().z());
    const double diag = f->box().diagonal().norm(), delta = 1e-4 * diag;
    int projected = 0;
    for (int i = 0; i < 200 && projected < 20; ++i) {
      const Vector3d p(ux(rng), uy(rng), uz(rng));
      Vector3d s;
      try {
        s = project_to_surface(*f, p);  // from anywhere: may fail, e.g. at a vanishing gradient
      } catch (const Error&) {
        continue;
      }
      EXPECT_NEAR(f->value(s), f->isovalue(), 1e-10 * (1 + std::abs(f->isovalue()))) << name;
      // From a point just off the surface (as mesh vertices are), it lands next to where it started.
      const Vector3d q = project_to_surface(*f, s + delta * random_unit(rng));
      EXPECT_NEAR(f->value(q), f->isovalue(), 1e-10 * (1 + std::abs(f->isovalue()))) << name;
      EXPECT_LT((q - s).norm(), 2 * delta) << name;
      ++projected;
    }
    EXPECT_EQ(projected, 20) << name;
  }
}

TEST(ExactCurvature, ZeroGradientThrows) {
  auto ell = make_field("ellipsoid");
  EXPECT_THROW(exact_curvature(*ell, Vector3d::Zero()), Error);
  EXPECT_THROW(project_to_surface(*ell, Vector3d::Zero()), Error);
}
