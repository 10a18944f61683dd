// Prantl et al.'s per-triangle estimator (double reference): the corrected closed form, the
// 2-edge/3-edge identity of H, the sphere and the f1/f2 protocol (SEEDS-SPEC 4.2, Appendix A4).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <random>

#include "curvature/detail/local_geometry.h"
#include "curvature/prantl.h"
#include "curvature/reference.h"
#include "estimator_protocols.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;
using curvature::TriangleShape;
using Arr3 = std::array<std::array<double, 3>, 3>;

// Random triangles with unit normals tilted from the face normal, as on a curved surface.
struct RandomTriangle {
  Arr3 p, n;
};
RandomTriangle random_triangle(std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1, 1);
  RandomTriangle t;
  for (auto& q : t.p)
    for (double& c : q) c = u(gen);
  const Eigen::Vector3d a(t.p[0][0], t.p[0][1], t.p[0][2]), b(t.p[1][0], t.p[1][1], t.p[1][2]),
      c(t.p[2][0], t.p[2][1], t.p[2][2]);
  const Eigen::Vector3d m = (b - a).cross(c - a).normalized();
  for (auto& q : t.n) {
    const Eigen::Vector3d v = (m + 0.3 * Eigen::Vector3d(u(gen), u(gen), u(gen))).normalized();
    q = {v.x(), v.y(), v.z()};
  }
  return t;
}

// The closed-form inverse equals an LDL^T solve of the same normal equations.
TEST(Prantl, ClosedFormMatchesLdlt) {
  std::mt19937 gen(5);
  int solved = 0;
  for (int k = 0; k < 2000; ++k) {
    const RandomTriangle t = random_triangle(gen);
    TriangleShape s;
    if (!curvature::prantl_triangle(t.p, t.n, 3, s)) continue;
    ++solved;
    // The same system, built independently and solved by LDL^T.
    Eigen::Vector3d P[3], N[3];
    for (int j = 0; j < 3; ++j)
      P[j] = {t.p[j][0], t.p[j][1], t.p[j][2]}, N[j] = {t.n[j][0], t.n[j][1], t.n[j][2]};
    const Eigen::Vector3d tu = (P[1] - P[0]).normalized();
    const Eigen::Vector3d tv = tu.cross(P[2] - P[0]).normalized().cross(tu);
    Eigen::Matrix3d B = Eigen::Matrix3d::Zero();
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), x;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d e = P[i] - P[(i + 1) % 3], dn = N[i] - N[(i + 1) % 3];
      const Eigen::Matrix<double, 2, 3> rows =
          (Eigen::Matrix<double, 2, 3>() << e.dot(tu), e.dot(tv), 0, 0, e.dot(tu), e.dot(tv))
              .finished();
      B += rows.transpose() * rows;
      c += rows.transpose() * Eigen::Vector2d(dn.dot(tu), dn.dot(tv));
    }
    ASSERT_TRUE(curvature::detail::ldlt_solve<3>(B, c, x));
    const double scale = x.norm() + 1;
    ASSERT_NEAR(s.L, x[0], 1e-9 * scale);
    ASSERT_NEAR(s.M, x[1], 1e-9 * scale);
    ASSERT_NEAR(s.N, x[2], 1e-9 * scale);
  }
  EXPECT_GT(solved, 1900);
}

// A property of the method: H from two edges equals H from three; K differs.
TEST(Prantl, TwoAndThreeEdgesGiveTheSameH) {
  std::mt19937 gen(9);
  double worst_h = 0, largest_k = 0;
  for (int k = 0; k < 10000; ++k) {
    const RandomTriangle t = random_triangle(gen);
    TriangleShape s2, s3;
    if (!curvature::prantl_triangle(t.p, t.n, 2, s2) ||
        !curvature::prantl_triangle(t.p, t.n, 3, s3))
      continue;
    const double scale = std::abs(s3.L) + std::abs(s3.M) + std::abs(s3.N);
    worst_h = std::max(worst_h, std::abs(s2.H() - s3.H()) / scale);
    largest_k = std::max(largest_k, std::abs(s2.K() - s3.K()) / (scale * scale));
  }
  std::printf("  relative |H2 - H3| <= %.2e, |K2 - K3| up to %.2e\n", worst_h, largest_k);
  EXPECT_LT(worst_h, 1e-9);
  EXPECT_GT(largest_k, 1e-3);
}

TEST(Prantl, DegenerateTrianglesAreSkipped) {
  TriangleShape s;
  const Arr3 n = {{{0, 0, 1}, {0, 0, 1}, {0, 0, 1}}};
  EXPECT_FALSE(curvature::prantl_triangle({{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}}, n, 3, s));
  EXPECT_FALSE(curvature::prantl_triangle({{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}}}, n, 3, s));
  EXPECT_FALSE(curvature::prantl_triangle({{{0, 0, 0}, {1, 0, 0}, {0.5, 1e-4, 0}}}, n, 2, s));
  EXPECT_TRUE(curvature::prantl_triangle({{{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}}}, n, 3, s));
  EXPECT_EQ(s.H(), 0);
}

// P-EV1: the sphere of radius 6 with exact normals, both variants, both averagings.
TEST(Prantl, SphereWithExactNormalsAtRoundingLevel) {
  const double R = 6;
  const Mesh m = icosphere(4, float(R));
  std::vector<Vec3f> n;
  for (const Vec3f& p : m.positions) {
    const double l = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    n.push_back({float(p[0] / l), float(p[1] / l), float(p[2] / l)});
  }
  curvature::Options o;
  o.vertex_normals = &n;
  for (int edges : {2, 3})
    for (auto avg : {curvature::PrantlAveraging::area, curvature::PrantlAveraging::uniform}) {
      const CurvatureField f = curvature::estimate_prantl_reference(m, o, edges, avg);
      EXPECT_TRUE(f.dir1.empty() && f.dir2.empty() && f.dcurv.empty());
      double mse_h = 0, mse_k = 0;
      for (std::size_t i = 0; i < f.size(); ++i) {
        mse_h += std::pow(f.H[i] - 1 / R, 2), mse_k += std::pow(f.K[i] - 1 / (R * R), 2);
        ASSERT_EQ(f.unreliable[i], 0);
      }
      mse_h /= double(f.size()), mse_k /= double(f.size());
      std::printf("  %d edges, %s: MSE H %.2e K %.2e (App. A4 2.4e-18 / 2.6e-19 in double, "
                  "paper 7.8e-17 / 8.2e-16)\n",
                  edges, avg == curvature::PrantlAveraging::area ? "area" : "uniform", mse_h,
                  mse_k);
      // float positions and normals bound what can be reached: 1e-12 (SEEDS-SPEC 4.2 (a)).
      EXPECT_LT(mse_h, 1e-12);
      EXPECT_LT(mse_k, 1e-12);
    }
}

// P-EV2: f1 and f2 from random points, exact normals; MSE against App. A4 and falling with N
// (f1 at 15k points and both at 60k are in bench_estimators).
TEST(Prantl, HeightfieldsConvergeWithPointCount) {
  struct Row {
    const char* f;
    int n;
    double h3, k3, rk;  // App. A4: P3 H and K (area averaging), Rusinkiewicz K
  };
  const Row rows[] = {{"f1", 1000, 1.72e-2, 2.58e-3, 2.83e-3},
                      {"f1", 4000, 5.55e-3, 4.32e-3, 3.73e-3},
                      {"f2", 1000, 8.00e-3, 6.53e-3, 6.34e-3},
                      {"f2", 4000, 1.87e-3, 1.56e-3, 1.49e-3},
                      {"f2", 15000, 4.81e-4, 3.97e-4, 3.77e-4}};
  double prev_h = 1e9;
  for (const Row& r : rows) {
    if (r.n == 1000) prev_h = 1e9;
    const Heightfield h = heightfield(r.f, r.n);
    curvature::Options o;
    o.vertex_normals = &h.normals;
    const CurvatureField p3 = curvature::estimate_prantl_reference(h.mesh, o, 3);
    const CurvatureField p2 = curvature::estimate_prantl_reference(h.mesh, o, 2);
    const CurvatureField rz = curvature::estimate_reference(h.mesh, o);
    const double h3 = mse(p3.H, h.H, h.inner), k3 = mse(p3.K, h.K, h.inner);
    const double h2 = mse(p2.H, h.H, h.inner), k2 = mse(p2.K, h.K, h.inner);
    const double rk = mse(rz.K, h.K, h.inner);
    std::printf("  %s %5d: P3 H %.2e K %.2e | P2 H %.2e K %.2e | Rusinkiewicz H %.2e K %.2e | "
                "App. A4 P3 %.2e %.2e\n",
                r.f, r.n, h3, k3, h2, k2, mse(rz.H, h.H, h.inner), rk, r.h3,
                r.k3);
    EXPECT_LT(h3, 2 * r.h3);
    EXPECT_GT(h3, r.h3 / 2);
    // f1's K error hangs on the few points near its peak, so another random point set gives
    // another MSE (ours is up to 2.1x App. A4's, Rusinkiewicz's alike): compare the ratio to
    // Rusinkiewicz on the same mesh instead.
    const double ratio = k3 / rk, app_ratio = r.k3 / r.rk;
    EXPECT_NEAR(ratio, app_ratio, 0.25 * app_ratio);
    EXPECT_LT(h3, prev_h);
    prev_h = h3;
    EXPECT_NEAR(h2, h3, 1e-6 * h3);  // identical H, up to float storage
    if (r.n >= 15000) {
      EXPECT_NEAR(k2, k3, 0.05 * k3);
    }
  }
}

}  // namespace
}  // namespace isocurv::test
