// The catalogue: names, analytic derivatives vs finite differences, boxes, the C60 geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>

#include "core/error.h"
#include "datasets/c60.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"

using namespace isocurv;
using namespace isocurv::datasets;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// Fourth-order central difference of a vector-valued function along axis a.
template <class F>
auto derivative(F&& f, const Vector3d& p, int a, double h) {
  Vector3d e = Vector3d::Zero();
  e[a] = h;
  // Evaluated into R: an Eigen expression returned by `auto` would refer to dead temporaries.
  using R = std::decay_t<decltype(f(p))>;
  const R plus1 = f(p + e), minus1 = f(p - e), plus2 = f(p + 2 * e), minus2 = f(p - 2 * e);
  return R((8.0 * (plus1 - minus1) - (plus2 - minus2)) / (12.0 * h));
}

// Random points in the box, and as many again projected onto the surface (where curvature matters).
std::vector<Vector3d> test_points(const Field& f, int n, unsigned seed) {
  std::mt19937 rng(seed);
  const auto& b = f.box();
  std::uniform_real_distribution<double> ux(b.min().x(), b.max().x()), uy(b.min().y(), b.max().y()),
      uz(b.min().z(), b.max().z());
  std::vector<Vector3d> pts;
  int surface = 0;
  for (int i = 0; i < 50 * n && (int)pts.size() < 2 * n; ++i) {
    const Vector3d p(ux(rng), uy(rng), uz(rng));
    if ((int)pts.size() < n) {
      pts.push_back(p);
      continue;
    }
    const Vector3d g = f.gradient(p);
    if (g.norm() == 0 || std::abs(f.value(p) - f.isovalue()) / g.norm() > 0.05 * b.diagonal().norm()) continue;
    try {
      const Vector3d q = project_to_surface(f, p);
      if (b.contains(q)) {
        pts.push_back(q);
        ++surface;
      }
    } catch (const Error&) {
    }
  }
  EXPECT_GT(surface, n / 2) << f.name();
  return pts;
}

}  // namespace

TEST(Fields, CatalogueNamesAndDefault) {
  const auto names = field_names();
  const std::vector<std::string> expected = {"sphere", "torus",          "ellipsoid", "gyroid",   "schwarz_p",
                                             "f1",     "f2",             "marschner_lobb", "hydrogen", "buckyball"};
  EXPECT_EQ(names, expected);
  EXPECT_NE(std::find(names.begin(), names.end(), kDefaultDataset), names.end());
  for (const auto& n : names) {
    auto f = make_field(n);
    EXPECT_EQ(f->name(), n);
    EXPECT_FALSE(f->info().description.empty());
    EXPECT_TRUE((f->box().sizes().array() > 0).all()) << n;
  }
  EXPECT_THROW(make_field("teapot"), Error);
}

TEST(Fields, GradientAndHessianMatchFiniteDifferences) {
  for (const auto& name : field_names()) {
    auto f = make_field(name);
    const double h = 1e-4 * f->box().diagonal().norm();
    const auto pts = test_points(*f, 100, 11);
    // Tolerances relative to the field's typical derivative magnitudes.
    double gscale = 0, hscale = 0;
    for (const auto& p : pts) {
      gscale = std::max(gscale, f->gradient(p).norm());
      hscale = std::max(hscale, f->hessian(p).norm());
    }
    ASSERT_GT(gscale, 0) << name;
    for (const auto& p : pts) {
      Vector3d g_fd;
      Matrix3d h_fd;
      for (int a = 0; a < 3; ++a) {
        g_fd[a] = derivative([&](const Vector3d& q) { return f->value(q); }, p, a, h);
        h_fd.col(a) = derivative([&](const Vector3d& q) { return f->gradient(q); }, p, a, h);
      }
      EXPECT_LT((f->gradient(p) - g_fd).norm(), 1e-6 * gscale) << name << " at " << p.transpose();
      EXPECT_LT((f->hessian(p) - h_fd).norm(), 1e-6 * hscale) << name << " at " << p.transpose();
      EXPECT_LT((f->hessian(p) - f->hessian(p).transpose()).norm(), 1e-12 * hscale) << name;
    }
  }
}

TEST(Fields, F1IsSmoothThroughItsRemovableSingularity) {
  auto f1 = make_field("f1");
  EXPECT_DOUBLE_EQ(f1->value(Vector3d(0, 0, 10)), 0.0);  // 10 sin(r)/r -> 10
  const Matrix3d h0 = f1->hessian(Vector3d::Zero());
  EXPECT_NEAR(h0(0, 0), -10.0 / 3.0, 1e-12);
  EXPECT_NEAR(h0(1, 1), -10.0 / 3.0, 1e-12);
  for (double r : {1e-6, 5e-3, 9.9e-3, 1.01e-2, 0.1}) {
    const Matrix3d hr = f1->hessian(Vector3d(r * 0.6, r * 0.8, 0));
    EXPECT_NEAR((hr - h0).norm(), 0.0, 2 * r) << r;  // continuous across the series switch
  }
  // The peak of the heightfield (solid below) is a cap: both curvatures positive, 10/3.
  const SurfaceCurvature c = exact_curvature(*f1, Vector3d(0, 0, 10));
  EXPECT_NEAR(c.k1, 10.0 / 3.0, 1e-12);
  EXPECT_NEAR(c.k2, 10.0 / 3.0, 1e-12);
  EXPECT_NEAR((c.normal - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(Fields, ClosedSurfacesStayInsideTheirBox) {
  for (const auto& name : field_names()) {
    auto f = make_field(name);
    if (!f->info().closed) continue;
    const auto& b = f->box();
    const double sign = f->inside() == volume::Inside::Above ? 1.0 : -1.0;
    const int n = 40;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side)
        for (int i = 0; i <= n; ++i)
          for (int j = 0; j <= n; ++j) {
            Vector3d p;
            p[axis] = side ? b.max()[axis] : b.min()[axis];
            p[(axis + 1) % 3] = b.min()[(axis + 1) % 3] + b.sizes()[(axis + 1) % 3] * i / n;
            p[(axis + 2) % 3] = b.min()[(axis + 2) % 3] + b.sizes()[(axis + 2) % 3] * j / n;
            ASSERT_LT(sign * (f->value(p) - f->isovalue()), 0) << name << " object reaches the box at " << p.transpose();
          }
  }
}

TEST(Fields, C60SitesFormATruncatedIcosahedron) {
  const double bond = 1.42;
  const auto sites = c60_sites(bond);
  ASSERT_EQ(sites.size(), 60u);
  for (std::size_t i = 0; i < sites.size(); ++i) {
    EXPECT_NEAR(sites[i].norm(), 0.5 * bond * std::sqrt(9 * (1 + std::sqrt(5.0)) / 2 + 10), 1e-12);
    int neighbours = 0;
    for (std::size_t j = 0; j < sites.size(); ++j) {
      if (i == j) continue;
      const double d = (sites[i] - sites[j]).norm();
      EXPECT_GT(d, bond - 1e-9);  // no closer pair, no duplicates
      neighbours += d < bond + 1e-9;
    }
    EXPECT_EQ(neighbours, 3);
  }
}

TEST(Fields, BuckyballIsACageOfBondTubes) {
  auto f = make_field("buckyball");
  const auto sites = c60_sites(1.42);
  // Bonds are filled: the density at every bond midpoint is above the isovalue.
  int bonds = 0;
  for (std::size_t i = 0; i < sites.size(); ++i)
    for (std::size_t j = i + 1; j < sites.size(); ++j)
      if ((sites[i] - sites[j]).norm() < 1.43) {
        EXPECT_GT(f->value(0.5 * (sites[i] + sites[j])), f->isovalue() + 0.1);
        ++bonds;
      }
  EXPECT_EQ(bonds, 90);
  // Faces are open: the centre of each pentagon (towards the icosahedron's vertices) and hexagon
  // (towards the dual dodecahedron's vertices) is below the isovalue. The centre is the mean of the 5
  // or 6 sites nearest that direction, which must be equidistant from it.
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::pair<Vector3d, int>> faces;
  for (int s = 0; s < 4; ++s)
    for (int c = 0; c < 3; ++c) {
      Vector3d v(0, (s & 1) ? -1 : 1, (s & 2) ? -phi : phi);
      faces.push_back({Vector3d(v[c], v[(c + 1) % 3], v[(c + 2) % 3]), 5});
      Vector3d w(0, (s & 1) ? -phi : phi, (s & 2) ? -1 / phi : 1 / phi);
      faces.push_back({Vector3d(w[c], w[(c + 1) % 3], w[(c + 2) % 3]), 6});
    }
  for (int s = 0; s < 8; ++s) faces.push_back({Vector3d((s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1), 6});
  ASSERT_EQ(faces.size(), 32u);
  for (const auto& [dir, k] : faces) {
    std::vector<Vector3d> near = sites;
    std::sort(near.begin(), near.end(), [&](const Vector3d& a, const Vector3d& b) {
      return a.normalized().dot(dir.normalized()) > b.normalized().dot(dir.normalized());
    });
    Vector3d centre = Vector3d::Zero();
    for (int i = 0; i < k; ++i) centre += near[i] / k;
    for (int i = 0; i < k; ++i) EXPECT_NEAR((near[i] - centre).norm(), (near[0] - centre).norm(), 1e-9);
    EXPECT_LT(f->value(centre), f->isovalue() - 0.1) << k << "-gon at " << dir.transpose();
  }
  EXPECT_EQ(f->info().euler_characteristic, std::optional<int>(2 - 2 * 31));
}

TEST(Fields, HydrogenIsNormalisedAndHasLobesAndRing) {
  auto f = make_field("hydrogen");
  EXPECT_NEAR(f->value(Vector3d(0, 0, 6)), 1.0, 1e-12);
  EXPECT_NEAR(f->gradient(Vector3d(0, 0, 6)).norm(), 0.0, 1e-12);
  EXPECT_GT(f->value(Vector3d(0, 0, -6)), f->isovalue());  // lower lobe
  EXPECT_GT(f->value(Vector3d(6, 0, 0)), f->isovalue());   // ring
  EXPECT_LT(f->value(Vector3d(0, 0, 0)), f->isovalue());   // gap between them
  EXPECT_LT(f->value(Vector3d(4, 0, 4 / std::sqrt(2.0))), f->isovalue());  // nodal cone
}
