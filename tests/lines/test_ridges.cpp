// Ridges and valleys: on an ellipsoid they lie in its principal planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "line_surfaces.h"
#include "lines/reference.h"

namespace isocurv::lines {
namespace {

// Ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 with exact normals (the gradient's
// direction).
test::Surface ellipsoid(double a, double b, double c, int level) {
  Mesh m = test::icosphere(level, {a, b, c});
  std::vector<Vec3f> normals;
  for (const Vec3f &p : m.positions) {
    const double g[3] = {p[0] / (a * a), p[1] / (b * b), p[2] / (c * c)};
    const double n = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    normals.push_back({float(g[0] / n), float(g[1] / n), float(g[2] / n)});
  }
  return test::with_curvature(std::move(m), &normals);
}

TEST(Ridges, EllipsoidRidgesLieInItsPrincipalPlanes) {
  const test::Surface s = ellipsoid(1.5, 1.0, 0.6, 5);
  Options o;
  o.lines = parse_line_selection("ridges,valleys");
  const Segments segs = extract_reference(s.mesh, s.field, Camera{}, o);
  const double edge = test::mean_edge(s.mesh);
  double length = 0;
  for (const Segment &g : segs) {
    EXPECT_EQ(g.type,
              LineType::ridge); // a convex surface has no valleys (k2 > 0)
    for (const Vec3f &q : {g.a, g.b})
      EXPECT_LE(std::fabs(q[2]), edge)
          << "ridge point off the z = 0 plane: " << q[0] << " " << q[1] << " " << q[2];
    length += test::seg_length(g.a, g.b);
  }
  // The ridge of k1 (the curvature across the ellipse of the two longest axes) is that whole
  // ellipse, z = 0 with semi-axes a = 1.5, b = 1: its perimeter by Ramanujan's formula,
  // pi (3 (a + b) - sqrt((3a + b)(a + 3b))) = 7.933, within 3% (the segments are chords of it
  // on a mesh of edge ~0.07, and it must be found whole, not in pieces).
  const double a = 1.5, b = 1.0, pi = 3.14159265358979;
  const double perimeter = pi * (3 * (a + b) - std::sqrt((3 * a + b) * (a + 3 * b)));
  EXPECT_NEAR(length, perimeter, 0.03 * perimeter);
}

TEST(Ridges, ValleysOfAnInsideOutEllipsoid) {
  // Reversing the winding (and the normals) turns ridges into valleys.
  test::Surface s = ellipsoid(1.5, 1.0, 0.6, 4);
  for (Tri &t : s.mesh.triangles)
    std::swap(t[1], t[2]);
  std::vector<Vec3f> inward;
  for (const Vec3f &n : s.field.normals)
    inward.push_back({-n[0], -n[1], -n[2]});
  s = test::with_curvature(s.mesh, &inward);
  Options o;
  o.lines = parse_line_selection("ridges,valleys");
  const Segments segs = extract_reference(s.mesh, s.field, Camera{}, o);
  ASSERT_GT(segs.size(), 0u);
  for (const Segment &g : segs)
    EXPECT_EQ(g.type, LineType::valley);
}

TEST(Ridges, NoneOnASphereAtTheDefaultThreshold) {
  const test::Surface s = test::with_curvature(test::icosphere(4));
  Options o;
  o.lines = parse_line_selection("ridges,valleys");
  EXPECT_EQ(extract_reference(s.mesh, s.field, Camera{}, o).size(), 0u);
}

} // namespace
} // namespace isocurv::lines
