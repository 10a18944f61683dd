// Hidden-line removal by ray casting and the SVG drawing: only visible lines
// are drawn.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/error.h"
#include "line_surfaces.h"
#include "lines/line_files.h"
#include "lines/polylines.h"
#include "lines/reference.h"
#include "lines/visibility.h"

namespace isocurv::lines {
namespace {

// A unit sphere at the origin and a small one (radius 0.3) right behind it,
// seen from +z.
test::Surface two_spheres() {
  Mesh big = test::icosphere(4),
       small = test::icosphere(3, {0.3, 0.3, 0.3}, {0, 0, -3});
  const auto base = std::uint32_t(big.positions.size());
  for (const Vec3f &p : small.positions)
    big.positions.push_back(p);
  for (const Tri &t : small.triangles)
    big.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return test::with_curvature(std::move(big));
}

Camera front() {
  Camera cam;
  cam.position = {0, 0, 5};
  cam.view_angle_deg = 30;
  return cam;
}

std::string temp_path(const char *name) {
  return (std::filesystem::temp_directory_path() /
          (std::to_string(::getpid()) + name))
      .string();
}

TEST(Visibility, TheSphereBehindIsHidden) {
  const test::Surface s = two_spheres();
  Options o;
  o.lines = parse_line_selection("contours");
  const Segments segs = extract_reference(s.mesh, s.field, front(), o);
  VisibilityTester vis(s.mesh);
  const std::vector<bool> keep = vis.visible_segments(segs, front());
  std::size_t big = 0, big_visible = 0, small = 0, small_visible = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const bool behind = segs[i].a[2] < -1.5;
    (behind ? small : big) += 1;
    (behind ? small_visible : big_visible) += keep[i];
  }
  ASSERT_GT(small, 20u);
  EXPECT_EQ(small_visible, 0u);
  EXPECT_EQ(big_visible,
            big); // the silhouette of the front sphere is all visible
  // Seen from the side, both are.
  Camera side;
  side.position = {6, 0, -1.5};
  side.focal_point = {0, 0, -1.5};
  side.view_up = {0, 1, 0};
  const Segments side_segs = extract_reference(s.mesh, s.field, side, o);
  const std::vector<bool> side_keep = vis.visible_segments(side_segs, side);
  std::size_t side_small = 0;
  for (std::size_t i = 0; i < side_segs.size(); ++i)
    side_small += side_keep[i] && side_segs[i].a[2] < -1.5;
  EXPECT_GT(side_small, 20u);
}

TEST(Svg, ParsesAndHoldsOnlyTheVisibleLines) {
  const test::Surface s = two_spheres();
  Options o;
  o.lines = parse_line_selection("contours");
  const Camera cam = front();
  const Segments segs = extract_reference(s.mesh, s.field, cam, o);
  const Segments visible = select_segments(
      segs, VisibilityTester(s.mesh).visible_segments(segs, cam));
  const std::string path = temp_path("-lines.svg");
  const int W = 400, H = 300;
  write_svg(path, join_segments(visible), cam, W, H);

  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement *root = parser->GetRootElement();
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->GetName(), "svg");
  // The big sphere's silhouette projects to a circle of radius tan(asin(1/5)) /
  // tan(15 deg) of the half height; the small one's (hidden) would be far
  // smaller.
  const double expect_r =
      std::tan(std::asin(0.2)) / std::tan(15 * test::kPi / 180) * H / 2;
  std::size_t polylines = 0, points = 0;
  for (int g = 0; g < root->GetNumberOfNestedElements(); ++g) {
    vtkXMLDataElement *group = root->GetNestedElement(g);
    if (std::string(group->GetName()) != "g")
      continue;
    for (int l = 0; l < group->GetNumberOfNestedElements(); ++l) {
      vtkXMLDataElement *line = group->GetNestedElement(l);
      ASSERT_STREQ(line->GetName(), "polyline");
      EXPECT_STREQ(group->GetAttribute("id"), "contours");
      ++polylines;
      std::stringstream in(line->GetAttribute("points"));
      double x, y;
      char comma;
      while (in >> x >> comma >> y) {
        ++points;
        EXPECT_NEAR(std::hypot(x - W / 2.0, y - H / 2.0), expect_r, 1.0);
      }
    }
  }
  EXPECT_EQ(polylines, 1u);
  EXPECT_GT(points, 50u);
  std::filesystem::remove(path);
}

TEST(Svg, ProjectMatchesTheCamera) {
  Camera cam;
  cam.position = {0, 0, 4};
  cam.view_angle_deg = 40;
  auto c = project(cam, {0, 0, 0}, 200, 100);
  EXPECT_NEAR(c[0], 100, 1e-9);
  EXPECT_NEAR(c[1], 50, 1e-9);
  EXPECT_NEAR(c[2], 4, 1e-9);
  // the top edge of the picture: tan(20 deg) * depth above the axis; +x to the
  // right
  auto top = project(cam, {0, 4 * std::tan(20 * test::kPi / 180), 0}, 200, 100);
  EXPECT_NEAR(top[1], 0, 1e-9);
  EXPECT_GT(project(cam, {1, 0, 0}, 200, 100)[0], 100);
  cam.ortho = true;
  cam.parallel_scale = 2;
  EXPECT_NEAR(project(cam, {0, -2, 0}, 200, 100)[1], 100, 1e-9);
  EXPECT_NEAR(project(cam, {4, 0, 0}, 200, 100)[0], 200, 1e-9);
}

TEST(Svg, BadSizeIsAnError) {
  EXPECT_THROW(write_svg(temp_path("-bad.svg"), Polylines{}, Camera{}, 4, 4000),
               Error);
  EXPECT_FALSE(std::filesystem::exists(temp_path("-bad.svg")));
}

TEST(Vtp, WritesLinesWithTheirArrays) {
  const test::Surface s = test::with_curvature(test::icosphere(3));
  const Polylines p =
      join_segments(extract_reference(s.mesh, s.field, front(), Options{}));
  const auto poly = to_polydata(p);
  EXPECT_EQ(poly->GetNumberOfLines(), vtkIdType(p.line_count()));
  ASSERT_NE(poly->GetCellData()->GetArray("LineType"), nullptr);
  ASSERT_NE(poly->GetCellData()->GetArray("Strength"), nullptr);
  const std::string path = temp_path("-lines.vtp");
  write_vtp(path, p);
  EXPECT_GT(std::filesystem::file_size(path), 100u);
  std::filesystem::remove(path);
}

} // namespace
} // namespace isocurv::lines
