// Occluding contours on a sphere (seeds spec G-LINE1/2 acceptance (a)) and
// their polylines.
#include <gtest/gtest.h>

#include <cmath>

#include "line_surfaces.h"
#include "lines/polylines.h"
#include "lines/reference.h"

namespace isocurv::lines {
namespace {

using test::kPi;

Options contours_only() {
  Options o;
  o.lines = parse_line_selection("contours");
  return o;
}

TEST(Contours, SphereOrthographicLiesOnTheEquatorWithLength2Pi) {
  const test::Surface s = test::with_curvature(test::icosphere(5));
  Camera cam;
  cam.position = {0, 0, 10};
  cam.focal_point = {0, 0, 0};
  cam.ortho = true;
  const Segments segs =
      extract_reference(s.mesh, s.field, cam, contours_only());
  ASSERT_GT(segs.size(), 100u);
  const double edge = test::mean_edge(s.mesh);
  double length = 0;
  for (const Segment &g : segs) {
    EXPECT_EQ(g.type, LineType::contour);
    EXPECT_LE(std::fabs(g.a[2]), edge);
    EXPECT_LE(std::fabs(g.b[2]), edge);
    length += test::seg_length(g.a, g.b);
  }
  EXPECT_NEAR(length, 2 * kPi, 0.01 * 2 * kPi);

  // Joined: one closed loop through every segment.
  const Polylines p = join_segments(segs);
  ASSERT_EQ(p.line_count(), 1u);
  EXPECT_EQ(p.offsets[1] - p.offsets[0], segs.size() + 1);
  EXPECT_EQ(p.points.front(), p.points.back());
  EXPECT_NEAR(p.length(LineType::contour), length, 1e-4);
}

TEST(Contours, SpherePerspectiveIsTheCircleOfTangency) {
  const test::Surface s = test::with_curvature(test::icosphere(5));
  const double D = 5;
  Camera cam;
  cam.position = {0, 0, D};
  cam.focal_point = {0, 0, 0};
  const Segments segs =
      extract_reference(s.mesh, s.field, cam, contours_only());
  ASSERT_GT(segs.size(), 100u);
  const double z0 = 1 / D, r0 = std::sqrt(1 - 1 / (D * D));
  for (const Segment &g : segs)
    for (const Vec3f &q : {g.a, g.b}) {
      EXPECT_NEAR(q[2], z0, 1e-3);
      EXPECT_NEAR(std::hypot(q[0], q[1]), r0, 1e-3);
    }
}

TEST(Contours, TorusFromTheSideGivesClosedLoops) {
  const test::Surface s =
      test::with_curvature(test::torus_mesh(1, 0.4, 96, 48));
  Camera cam;
  cam.position = {0.3, -6, 2};
  cam.focal_point = {0, 0, 0};
  cam.view_up = {0, 0, 1};
  const Segments segs =
      extract_reference(s.mesh, s.field, cam, contours_only());
  const Polylines p = join_segments(segs);
  ASSERT_GE(p.line_count(), 1u);
  std::size_t points = 0;
  for (std::size_t l = 0; l < p.line_count(); ++l) {
    // every contour of a smooth closed surface is a closed curve
    EXPECT_EQ(p.points[p.offsets[l]], p.points[p.offsets[l + 1] - 1])
        << "line " << l;
    points += p.offsets[l + 1] - p.offsets[l] - 1;
  }
  EXPECT_EQ(points, segs.size());
}

} // namespace
} // namespace isocurv::lines
