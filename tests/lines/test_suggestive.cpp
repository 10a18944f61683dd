// Suggestive contours: none on a sphere or on a torus seen along its axis, and
// the inflection lines of a corrugated sheet (seeds spec G-LINE1/2 acceptance
// (b) and (c)).
#include <gtest/gtest.h>

#include <cmath>

#include "line_surfaces.h"
#include "lines/reference.h"

namespace isocurv::lines {
namespace {

using test::kPi;

Options suggestive_only() {
  Options o;
  o.lines = parse_line_selection("suggestive");
  return o;
}

std::size_t count_type(const Segments &segs, LineType t) {
  std::size_t n = 0;
  for (const Segment &g : segs)
    n += g.type == t;
  return n;
}

TEST(Suggestive, NoneOnASphere) {
  const test::Surface s = test::with_curvature(test::icosphere(5));
  for (const std::array<double, 3> eye :
       {std::array<double, 3>{0, 0, 5}, {3, -2, 1}, {0.2, 8, -4}}) {
    for (bool ortho : {false, true}) {
      Camera cam;
      cam.position = eye;
      cam.ortho = ortho;
      Options o = suggestive_only();
      o.suggestive_threshold =
          0; // any crossing with a positive derivative would count
      EXPECT_EQ(extract_reference(s.mesh, s.field, cam, o).size(), 0u);
    }
  }
}

TEST(Suggestive, NoneOnATorusSeenAlongItsAxis) {
  const test::Surface s =
      test::with_curvature(test::torus_mesh(1, 0.4, 96, 48));
  for (bool ortho : {false, true}) {
    Camera cam;
    cam.position = {0, 0, 6};
    cam.ortho = ortho;
    Options o = suggestive_only();
    o.lines.contours = true;
    const Segments segs = extract_reference(s.mesh, s.field, cam, o);
    EXPECT_EQ(count_type(segs, LineType::suggestive), 0u)
        << (ortho ? "ortho" : "perspective");
    EXPECT_GT(count_type(segs, LineType::contour),
              0u); // the view itself does find lines
  }
}

// z = 0.3 cos x over [0, 6 pi] x [0, 3], 600 x 100 cells, exact normals, seen
// along (sin 45, 0, cos 45). kr vanishes on the inflection lines x = pi/2 + k
// pi; D_w kr has the sign of -sin x there, so only x = 3pi/2, 7pi/2, 11pi/2
// carry suggestive contours.
TEST(Suggestive, CorrugatedSheetInflectionLines) {
  const double a = 0.3, X = 6 * kPi, Y = 3;
  Mesh m = test::grid_mesh(600, 100, false, false, [&](double s, double t) {
    return std::array<double, 3>{X * s, Y * t, a * std::cos(X * s)};
  });
  std::vector<Vec3f> normals;
  for (const Vec3f &p : m.positions) {
    const double slope = -a * std::sin(p[0]), n = std::sqrt(1 + slope * slope);
    normals.push_back({float(-slope / n), 0, float(1 / n)});
  }
  const test::Surface s = test::with_curvature(std::move(m), &normals);
  Camera cam;
  cam.ortho = true;
  cam.focal_point = {X / 2, Y / 2, 0};
  const double c = std::sqrt(0.5);
  cam.position = {X / 2 + 10 * c, Y / 2, 10 * c};
  cam.view_up = {-c, 0, c};
  const Segments segs =
      extract_reference(s.mesh, s.field, cam, suggestive_only());
  ASSERT_GT(segs.size(), 0u);
  const double lines[3] = {1.5 * kPi, 3.5 * kPi, 5.5 * kPi};
  constexpr int kBins = 300; // along y, for the coverage
  std::vector<std::vector<bool>> covered(3, std::vector<bool>(kBins, false));
  for (const Segment &g : segs) {
    int which = -1;
    for (int l = 0; l < 3; ++l)
      if (std::fabs(g.a[0] - lines[l]) <= 0.02 * kPi &&
          std::fabs(g.b[0] - lines[l]) <= 0.02 * kPi)
        which = l;
    ASSERT_GE(which, 0) << "segment at x = " << g.a[0] << " .. " << g.b[0]
                        << ", y = " << g.a[1];
    const double y0 = std::min(g.a[1], g.b[1]), y1 = std::max(g.a[1], g.b[1]);
    for (int b = 0; b < kBins; ++b) {
      const double yc = (b + 0.5) * Y / kBins;
      if (yc >= y0 && yc <= y1)
        covered[which][b] = true;
    }
  }
  for (int l = 0; l < 3; ++l) {
    int n = 0;
    for (bool b : covered[l])
      n += b;
    EXPECT_GE(n, 0.95 * kBins) << "inflection line x = " << lines[l];
  }
}

} // namespace
} // namespace isocurv::lines
