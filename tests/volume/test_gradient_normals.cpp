// gradient_normals against the exact normals of analytic fields.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "volume/from_dense.h"
#include "volume/gradient_normals.h"

using namespace isocurv;
using namespace isocurv::volume;

namespace {

/// A 48^3 sampling of f(p) = R - |p - c| (positive inside), world = origin + index * spacing.
Volume sphere_field(Inside inside, double spacing, openvdb::Vec3d origin, openvdb::Vec3d centre, double radius) {
  const int n = 48;
  std::vector<float> data(std::size_t(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const openvdb::Vec3d p = origin + spacing * openvdb::Vec3d(x, y, z);
        const double d = radius - (p - centre).length();
        data[(std::size_t(z) * n + y) * n + x] = float(inside == Inside::Above ? d : -d);
      }
  auto xf = openvdb::math::Transform::createLinearTransform(spacing);
  xf->postTranslate(origin);
  return from_dense(data.data(), {n, n, n}, xf, {"sphere", "generated", "float", "", inside});
}

double worst_angle_deg(const Volume& v, openvdb::Vec3d centre, double radius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Positions points;
  std::vector<openvdb::Vec3d> truth;
  while (points.size() < 2000) {
    openvdb::Vec3d d(u(rng), u(rng), u(rng));
    if (d.length() < 1e-3) continue;
    d.normalize();
    const openvdb::Vec3d p = centre + radius * d;
    points.push_back({float(p.x()), float(p.y()), float(p.z())});
    truth.push_back(d);
  }
  const auto normals = gradient_normals(v, points);
  double worst = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const openvdb::Vec3d n(normals[i][0], normals[i][1], normals[i][2]);
    EXPECT_NEAR(n.length(), 1.0, 1e-5);
    worst = std::max(worst, std::acos(std::min(1.0, n.dot(truth[i]))) * 180 / M_PI);
  }
  return worst;
}

}  // namespace

TEST(VolumeGradientNormals, SphereFieldOutwardForBothInsideConventions) {
  const openvdb::Vec3d origin(-1.2, -1.2, -1.2), centre(0.1, -0.05, 0.02);
  for (Inside inside : {Inside::Above, Inside::Below}) {
    const Volume v = sphere_field(inside, 0.05, origin, centre, 0.8);
    EXPECT_LT(worst_angle_deg(v, centre, 0.8), 0.5) << (inside == Inside::Above ? "above" : "below");
  }
}

TEST(VolumeGradientNormals, AnisotropicSpacingUsesWorldGradient) {
  // f = 2x + y (world), sampled with spacing (0.5, 0.25, 1): the world gradient is (2, 1, 0)
  // whatever the spacing; index-space differences alone would give a different direction.
  const int n = 8;
  std::vector<float> data(std::size_t(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) data[(std::size_t(z) * n + y) * n + x] = float(2 * (0.5 * x) + 0.25 * y);
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  m(0, 0) = 0.5;
  m(1, 1) = 0.25;
  auto xf = openvdb::math::Transform::createLinearTransform(m);
  const Volume v = from_dense(data.data(), {n, n, n}, xf, {"plane", "generated", "float", "", Inside::Above});
  // Includes a point on the domain border (one-sided differences) and one outside it (clamped).
  const auto normals = gradient_normals(v, {{1.3f, 0.7f, 3.1f}, {0.0f, 0.0f, 0.0f}, {9.0f, 9.0f, 9.0f}});
  const double s = 1 / std::sqrt(5.0);
  for (const auto& nrm : normals) {
    EXPECT_NEAR(nrm[0], -2 * s, 1e-5);  // outward = -gradient for Inside::Above
    EXPECT_NEAR(nrm[1], -1 * s, 1e-5);
    EXPECT_NEAR(nrm[2], 0, 1e-5);
  }
}

TEST(VolumeGradientNormals, FlatFieldGivesZeroVector) {
  std::vector<float> data(27, 1.0f);
  const Volume v = from_dense(data.data(), {3, 3, 3}, nullptr, {"flat", "generated", "float", "", Inside::Above});
  const auto normals = gradient_normals(v, {{1, 1, 1}});
  EXPECT_EQ(normals[0], (Vec3f{0, 0, 0}));
  EXPECT_TRUE(gradient_normals(v, {}).empty());
}
