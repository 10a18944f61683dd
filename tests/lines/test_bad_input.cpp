// Bad input to the lines stage: one clear Error, never NaN segments.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/cl_device.h"
#include "core/error.h"
#include "line_surfaces.h"
#include "lines/extract.h"
#include "lines/reference.h"

namespace isocurv::lines {
namespace {

TEST(LinesInput, SelectionParsing) {
  const LineSelection s = parse_line_selection("contours,ridges");
  EXPECT_TRUE(s.contours && s.ridges && !s.suggestive && !s.valleys);
  EXPECT_EQ(s.to_string(), "contours,ridges");
  EXPECT_TRUE(parse_line_selection("all").valleys);
  for (const char *bad :
       {"", "contours,", "bogus", "ridges,ridges", ",valleys"})
    EXPECT_THROW(parse_line_selection(bad), Error) << bad;
}

TEST(LinesInput, NoDcurvOnlyContours) {
  test::Surface s = test::with_curvature(test::icosphere(3));
  s.field.dcurv.clear();
  Options o; // contours and suggestive
  Camera cam;
  cam.position = {0, 0, 5};
  try {
    extract_reference(s.mesh, s.field, cam, o);
    FAIL() << "expected an Error";
  } catch (const Error &e) {
    EXPECT_NE(std::string(e.what()).find("dcurv"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("suggestive"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(extract(s.mesh, s.field, cam, o, Device::default_device()),
               Error);
  o.lines = parse_line_selection("contours");
  EXPECT_GT(extract_reference(s.mesh, s.field, cam, o).size(), 0u);
}

TEST(LinesInput, NoDirectionsOnlyContours) {
  test::Surface s = test::with_curvature(test::icosphere(3));
  s.field.dir1.clear();
  s.field.dir2.clear();
  s.field.dcurv.clear();
  Camera cam;
  cam.position = {0, 0, 5};
  for (const char *asked : {"suggestive", "ridges", "contours,valleys"}) {
    Options o;
    o.lines = parse_line_selection(asked);
    try {
      extract_reference(s.mesh, s.field, cam, o);
      FAIL() << "expected an Error for " << asked;
    } catch (const Error &e) {
      EXPECT_NE(std::string(e.what()).find("only contours"), std::string::npos) << e.what();
    }
    EXPECT_THROW(extract(s.mesh, s.field, cam, o, Device::default_device()), Error) << asked;
  }
  Options o;
  o.lines = parse_line_selection("contours");
  EXPECT_GT(extract(s.mesh, s.field, cam, o, Device::default_device()).size(), 0u);
  // Directions of the wrong length are still an error.
  s.field.dir1.resize(3);
  EXPECT_THROW(extract_reference(s.mesh, s.field, cam, o), Error);
}

TEST(LinesInput, MismatchedFieldAndBadIndices) {
  test::Surface s = test::with_curvature(test::icosphere(2));
  test::Surface short_field = s;
  short_field.field.k1.pop_back();
  EXPECT_THROW(extract_reference(short_field.mesh, short_field.field, Camera{},
                                 Options{}),
               Error);
  test::Surface bad = s;
  bad.mesh.triangles.push_back({0, 1, 99999});
  EXPECT_THROW(extract_reference(bad.mesh, bad.field, Camera{}, Options{}),
               Error);
  Options o;
  o.suggestive_angle_deg = 90;
  EXPECT_THROW(extract_reference(s.mesh, s.field, Camera{}, o), Error);
  o = Options{};
  o.ridge_threshold = -1;
  EXPECT_THROW(extract_reference(s.mesh, s.field, Camera{}, o), Error);
}

TEST(LinesInput, DegenerateFacesGiveNoSegmentAndNoNaN) {
  test::Surface s = test::with_curvature(test::icosphere(3));
  const std::size_t faces = s.mesh.triangles.size();
  // a repeated index, a zero-area sliver (three collinear vertices), a NaN
  // corner
  const Tri first = s.mesh.triangles[0];
  s.mesh.triangles.push_back({first[0], first[0], first[1]});
  const auto n = std::uint32_t(s.mesh.positions.size());
  for (int i = 0; i < 3; ++i)
    s.mesh.positions.push_back({float(i), 0, 0});
  s.mesh.positions.push_back({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  s.mesh.triangles.push_back({n, n + 1, n + 2});
  s.mesh.triangles.push_back({first[0], first[1], n + 3});
  for (int i = 0; i < 4; ++i) {
    s.field.normals.push_back({0, 0, 1});
    s.field.dir1.push_back({1, 0, 0});
    s.field.dir2.push_back({0, 1, 0});
    s.field.k1.push_back(i == 3 ? std::numeric_limits<float>::quiet_NaN()
                                : 1.f);
    s.field.k2.push_back(-1);
    s.field.dcurv.push_back({1, -1, 1, -1});
  }
  Options o;
  o.lines = parse_line_selection("all");
  Camera cam;
  cam.position = {0.5, 3, 0.2};
  for (int dev = 0; dev < 2; ++dev) {
    const Segments segs =
        dev ? extract(s.mesh, s.field, cam, o, Device::default_device())
            : extract_reference(s.mesh, s.field, cam, o);
    for (const Segment &g : segs) {
      EXPECT_LT(g.face, faces);
      for (float c :
           {g.a[0], g.a[1], g.a[2], g.b[0], g.b[1], g.b[2], g.strength})
        EXPECT_TRUE(std::isfinite(c));
    }
  }
}

} // namespace
} // namespace isocurv::lines
