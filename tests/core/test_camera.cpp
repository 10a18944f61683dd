// Named views and fitting a camera to a box (core/camera).
#include "core/camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"

namespace isocurv {
namespace {

using Vec = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

using vec3::dot;
using vec3::sub;
using vec3::cross;

void expect_vec(const Vec& got, const Vec& want, double tol = 1e-12) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << "component " << i;
}

TEST(Camera, NamesRoundTripAndUnknownNamesAreRefused) {
  for (const char* n : {"iso", "+x", "-x", "+y", "-y", "+z", "-z"})
    EXPECT_EQ(to_string(parse_named_view(n)), n);
  EXPECT_THROW(parse_named_view("front"), Error);
  EXPECT_THROW(parse_named_view("x"), Error);
}

TEST(Camera, AxisViewsLookAtTheCentreFromTheirSide) {
  Vec t, u;
  view_axes({NamedView::plus_x}, t, u);
  expect_vec(t, {1, 0, 0});
  expect_vec(u, {0, 0, 1});
  view_axes({NamedView::minus_y}, t, u);
  expect_vec(t, {0, -1, 0});
  view_axes({NamedView::plus_z}, t, u);
  expect_vec(t, {0, 0, 1});
  expect_vec(u, {0, 1, 0});
}

TEST(Camera, IsoIsTheThreeQuarterViewFromAbove) {
  // From -y, turned 35 degrees about +z, raised 30 degrees (vtkCamera Azimuth then Elevation).
  Vec t, u;
  view_axes({NamedView::iso}, t, u);
  const double a = 35 * kPi / 180, e = 30 * kPi / 180;
  expect_vec(t, {std::sin(a) * std::cos(e), -std::cos(a) * std::cos(e), std::sin(e)});
  EXPECT_NEAR(dot(t, u), 0, 1e-12);
  EXPECT_GT(u[2], 0.8);  // up stays mostly +z
}

TEST(Camera, AzimuthAndElevationTurnTheNamedView) {
  Vec t, u;
  ViewSpec s{NamedView::minus_y};
  s.azimuth_deg = 90;  // from -y about +z by +90: to +x
  view_axes(s, t, u);
  expect_vec(t, {1, 0, 0});
  s = {NamedView::minus_y};
  s.elevation_deg = 90;  // raised straight over the top: looking down, up turns to +y
  view_axes(s, t, u);
  expect_vec(t, {0, 0, 1});
  expect_vec(u, {0, 1, 0});
}

/// Largest |projected coordinate| of `points` as fractions of the half-height and half-width.
void points_in_image(const Camera& c, const std::vector<Vec>& points, double aspect, double& vert,
                     double& horiz) {
  const Vec back = c.toward_camera(), up = c.view_up, right = cross(up, back);
  const double tan_half = std::tan(0.5 * c.view_angle_deg * kPi / 180);
  vert = horiz = 0;
  for (const Vec& p : points) {
    const Vec d = sub(p, c.focal_point);
    double x = dot(d, right), y = dot(d, up);
    if (c.ortho) {
      x /= c.parallel_scale * aspect, y /= c.parallel_scale;
    } else {
      const double depth = dot(sub(c.position, p), back);
      ASSERT_GT(depth, 0) << "a point lies behind the eye";
      x /= depth * tan_half * aspect, y /= depth * tan_half;
    }
    vert = std::max(vert, std::abs(y)), horiz = std::max(horiz, std::abs(x));
  }
}

/// Largest |projected coordinate| of the box corners as a fraction of the half-height (vertical)
/// and half-width (horizontal) of the image.
void extent_in_image(const Camera& c, const std::array<double, 6>& b, double aspect,
                     double& vert, double& horiz) {
  std::vector<Vec> corners;
  for (int i = 0; i < 8; ++i) corners.push_back({b[(i & 1) ? 1 : 0], b[(i & 2) ? 3 : 2], b[(i & 4) ? 5 : 4]});
  points_in_image(c, corners, aspect, vert, horiz);
}

TEST(Camera, FitKeepsEveryCornerInsideTheMarginAndIsTight) {
  const std::array<double, 6> box{-3, 5, 0, 1, 10, 14};  // long in x, flat in y
  for (bool ortho : {false, true})
    for (NamedView v : {NamedView::iso, NamedView::plus_x, NamedView::minus_z, NamedView::plus_y})
      for (double aspect : {0.5, 1.0, 4.0 / 3.0, 3.0}) {
        ViewSpec s{v};
        s.ortho = ortho;
        const double margin = 0.1;
        const Camera c = fit_camera(box, s, aspect, margin);
        double vert, horiz;
        extent_in_image(c, box, aspect, vert, horiz);
        SCOPED_TRACE(to_string(v) + (ortho ? " ortho" : " perspective") + " aspect " +
                     std::to_string(aspect));
        EXPECT_LE(vert, 1 - margin + 1e-9);
        EXPECT_LE(horiz, 1 - margin + 1e-9);
        // Tight: the box touches the margin along one direction (perspective within 2%: the
        // focal point centres the box's parallel projection, not its perspective one).
        EXPECT_GT(std::max(vert, horiz), (1 - margin) * (ortho ? 1 - 1e-9 : 0.98));
      }
}

TEST(Camera, FitToPointsKeepsThemInsideAndFillsMoreThanTheirBox) {
  // Points along the box's long diagonal: seen from +z they leave most of the box's corners empty.
  std::vector<Vec> points;
  for (int i = 0; i <= 20; ++i) points.push_back({-3 + 0.4 * i, 0.05 * i, 10 + 0.2 * i});
  const std::array<double, 6> box{-3, 5, 0, 1, 10, 14};
  for (bool ortho : {false, true})
    for (NamedView v : {NamedView::iso, NamedView::plus_z, NamedView::minus_y}) {
      ViewSpec s{v};
      s.ortho = ortho;
      SCOPED_TRACE(to_string(v) + (ortho ? " ortho" : " perspective"));
      const Camera c = fit_camera_to_points(points, s, 4.0 / 3.0, 0.1);
      double vert, horiz, box_vert, box_horiz;
      points_in_image(c, points, 4.0 / 3.0, vert, horiz);
      EXPECT_LE(vert, 0.9 + 1e-9);
      EXPECT_LE(horiz, 0.9 + 1e-9);
      EXPECT_GT(std::max(vert, horiz), 0.9 * (ortho ? 1 - 1e-9 : 0.98));  // tight
      points_in_image(fit_camera(box, s, 4.0 / 3.0, 0.1), points, 4.0 / 3.0, box_vert, box_horiz);
      EXPECT_GE(std::max(vert, horiz), std::max(box_vert, box_horiz) - 1e-9);
    }
  // Eight corners are the box: the same camera as fit_camera's.
  std::vector<Vec> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back({box[(i & 1) ? 1 : 0], box[(i & 2) ? 3 : 2], box[(i & 4) ? 5 : 4]});
  const Camera a = fit_camera(box, ViewSpec{}, 1.5), b = fit_camera_to_points(corners, ViewSpec{}, 1.5);
  expect_vec(a.position, b.position);
  expect_vec(a.focal_point, b.focal_point);
  EXPECT_TRUE(std::isfinite(fit_camera_to_points({}, ViewSpec{}, 1).position[0]));
}

TEST(Camera, ZoomMagnifiesAndEmptyBoxesStillGiveACamera) {
  const std::array<double, 6> box{0, 1, 0, 1, 0, 1};
  ViewSpec s;
  const Camera c1 = fit_camera(box, s, 1);
  s.zoom = 2;
  const Camera c2 = fit_camera(box, s, 1);
  EXPECT_NEAR(std::tan(0.5 * c2.view_angle_deg * kPi / 180),
              0.5 * std::tan(0.5 * c1.view_angle_deg * kPi / 180), 1e-12);
  s.ortho = true;
  const Camera o2 = fit_camera(box, s, 1);
  s.zoom = 1;
  EXPECT_NEAR(o2.parallel_scale, 0.5 * fit_camera(box, s, 1).parallel_scale, 1e-12);

  const Camera e = fit_camera({1, -1, 0, 0, 0, 0}, ViewSpec{}, 1);  // inverted: empty
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(std::isfinite(e.position[i]));
  const Camera p = fit_camera({2, 2, 3, 3, 4, 4}, ViewSpec{}, 1);  // a point
  EXPECT_GT(std::sqrt(dot(sub(p.position, p.focal_point), sub(p.position, p.focal_point))), 0);
  expect_vec(p.focal_point, {2, 3, 4}, 1e-9);
}

TEST(Camera, ViewVectorIsPerPointInPerspectiveAndConstantInOrtho) {
  ViewSpec s{NamedView::plus_z};
  const std::array<double, 6> box{-1, 1, -1, 1, -1, 1};
  const Camera persp = fit_camera(box, s, 1);
  const Vec v = persp.view_vector({1, 0, 0});
  EXPECT_LT(v[0], 0);  // the eye is on the axis: from (1,0,0) it lies towards -x
  s.ortho = true;
  const Camera ortho = fit_camera(box, s, 1);
  expect_vec(ortho.view_vector({1, 0, 0}), {0, 0, 1});
}

TEST(Camera, AnatomicalViewsInRasAndLps) {
  // RAS: anterior is +y; LPS: anterior is -y. Superior is +z in both; superior views have
  // anterior up.
  auto [t, u] = anatomical_axes("anterior", AnatomicalFrame::ras);
  expect_vec(t, {0, 1, 0});
  expect_vec(u, {0, 0, 1});
  std::tie(t, u) = anatomical_axes("anterior", AnatomicalFrame::lps);
  expect_vec(t, {0, -1, 0});
  std::tie(t, u) = anatomical_axes("left", AnatomicalFrame::lps);
  expect_vec(t, {1, 0, 0});
  std::tie(t, u) = anatomical_axes("right", AnatomicalFrame::ras);
  expect_vec(t, {1, 0, 0});
  std::tie(t, u) = anatomical_axes("superior", AnatomicalFrame::ras);
  expect_vec(t, {0, 0, 1});
  expect_vec(u, {0, 1, 0});
  // LAS (NRRD's left-anterior-superior): right is -x, anterior +y
  std::tie(t, u) = anatomical_axes("right", AnatomicalFrame::las);
  expect_vec(t, {-1, 0, 0});
  std::tie(t, u) = anatomical_axes("anterior", AnatomicalFrame::las);
  expect_vec(t, {0, 1, 0});
  EXPECT_EQ(anatomical_frame_named("LPS"), AnatomicalFrame::lps);
  EXPECT_EQ(anatomical_frame_named("LAS"), AnatomicalFrame::las);
  EXPECT_FALSE(anatomical_frame_named(""));
  EXPECT_TRUE(is_anatomical_view("inferior"));
  EXPECT_FALSE(is_anatomical_view("+x"));
  EXPECT_THROW(anatomical_axes("front", AnatomicalFrame::ras), Error);
  // a ViewSpec with axes uses them (then its turns)
  ViewSpec s;
  s.axes = anatomical_axes("posterior", AnatomicalFrame::ras);
  Vec toward, up;
  view_axes(s, toward, up);
  expect_vec(toward, {0, -1, 0});
}

TEST(Camera, ViewUpReplacesTheViewsUpAndAlongTheViewIsRefused) {
  // headsq is stored head down: seen from -y with -z up, the face is upright.
  ViewSpec s{NamedView::minus_y};
  s.view_up = parse_direction("-z");
  Vec t, u;
  view_axes(s, t, u);
  expect_vec(t, {0, -1, 0});
  expect_vec(u, {0, 0, -1});
  // an oblique up is made perpendicular to the view
  s.view_up = parse_direction("1,-1,0");
  view_axes(s, t, u);
  expect_vec(u, {1, 0, 0}, 1e-12);
  s.view_up = parse_direction("0,2,0");
  EXPECT_THROW(view_axes(s, t, u), Error);
  for (const char* bad : {"0,0,0", "up", "1,2", "1,2,3,4", "nan,0,1"})
    EXPECT_THROW(parse_direction(bad), Error) << bad;
  expect_vec(parse_direction("0,0,-5"), {0, 0, -1});
}

TEST(Camera, RollTurnsThePictureAnticlockwise) {
  // From +z (right = +x, up = +y), a quarter turn anticlockwise brings what was on the right
  // (+x) to the top.
  ViewSpec s{NamedView::plus_z};
  s.roll_deg = 90;
  Vec t, u;
  view_axes(s, t, u);
  expect_vec(t, {0, 0, 1});
  expect_vec(u, {1, 0, 0}, 1e-12);
  s.roll_deg = 360;
  view_axes(s, t, u);
  expect_vec(u, {0, 1, 0}, 1e-12);
}

TEST(Camera, ElevationBeyondNinetyGoesOverTheTop) {
  // From +x, raised 120 degrees: past the top (+z), now on the -x side, above, upside down;
  // raised 180: from -x, with -z up. Continuous, never degenerate.
  ViewSpec s{NamedView::plus_x};
  Vec t, u;
  s.elevation_deg = 120;
  view_axes(s, t, u);
  expect_vec(t, {std::cos(120 * kPi / 180), 0, std::sin(120 * kPi / 180)}, 1e-12);
  EXPECT_NEAR(dot(t, u), 0, 1e-12);
  EXPECT_LT(u[2], 0);
  s.elevation_deg = 180;
  view_axes(s, t, u);
  expect_vec(t, {-1, 0, 0}, 1e-12);
  expect_vec(u, {0, 0, -1}, 1e-12);
}

TEST(Camera, AnatomicalIsoIsFromTheFrontAboveWithSuperiorUp) {
  for (AnatomicalFrame f : {AnatomicalFrame::ras, AnatomicalFrame::lps, AnatomicalFrame::las}) {
    const auto [t, u] = anatomical_axes("iso", f);
    const Vec anterior = anatomical_axes("anterior", f).first;
    EXPECT_NEAR(dot(t, anterior), std::cos(35 * kPi / 180) * std::cos(30 * kPi / 180), 1e-12);
    EXPECT_NEAR(t[2], std::sin(30 * kPi / 180), 1e-12);  // raised 30 degrees
    EXPECT_GT(u[2], 0.8);                                  // superior (+z) is up
    EXPECT_NEAR(dot(t, u), 0, 1e-12);
  }
}

}  // namespace
}  // namespace isocurv
