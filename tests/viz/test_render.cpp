// viz::render_png under a private Xvfb when there is no display.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "png_stats.h"
#include "test_surfaces.h"
#include "viz/color_map.h"
#include "viz/curvature_scene.h"
#include "viz/headless_display.h"
#include "viz/render.h"

namespace fs = std::filesystem;
using namespace isocurv;

namespace {

class VizRenderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("isocurv_viz_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);  // keep the images of a failure for a look
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

}  // namespace

TEST_F(VizRenderTest, EnsureDisplayProvidesOne) {
  viz::ensure_display();
  const char* display = std::getenv("DISPLAY");
  ASSERT_NE(display, nullptr);
  EXPECT_NE(std::string(display), "");
  viz::ensure_display();  // idempotent
}

TEST_F(VizRenderTest, TorusColouredByGaussianCurvatureShowsBothSigns) {
  // A slim torus: on the outer rim K = 1/(r(R+r)) is close to the hole's |K| = 1/(r(R-r)), so with
  // the range symmetric around zero both ends of the map show up.
  const auto torus = test::torus(1.f, 0.2f);
  viz::RenderOptions o;
  o.color = "K";
  o.width = 640;
  o.height = 480;
  o.title = "torus, Gaussian curvature";
  const std::string p = path("torus_K.png");
  viz::render_png(p, torus.mesh, torus.field, o);
  const test::PngStats s = test::png_stats(p);
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  EXPECT_GT(s.luminance_variance, 100.0) << "blank image";
  EXPECT_GT(s.bluish, 0.005) << "no negative-K (hole) colour";
  EXPECT_GT(s.reddish, 0.005) << "no positive-K (outer rim) colour";
}

TEST_F(VizRenderTest, SaddleColouredByMeanCurvatureShowsBothSigns) {
  const auto saddle = test::saddle();
  viz::RenderOptions o;  // H, 1024 x 768
  const std::string p = path("saddle_H.png");
  viz::render_png(p, saddle.mesh, saddle.field, o);
  const test::PngStats s = test::png_stats(p);
  EXPECT_EQ(s.width, 1024);
  EXPECT_EQ(s.height, 768);
  EXPECT_GT(s.luminance_variance, 100.0);
  EXPECT_GT(s.bluish, 0.005);
  EXPECT_GT(s.reddish, 0.005);
}

TEST_F(VizRenderTest, SaddleGaussianCurvatureIsAllNegative) {
  // K < 0 everywhere, so with a range symmetric around zero nothing is red.
  const auto saddle = test::saddle();
  viz::RenderOptions o;
  o.color = "K";
  o.width = 400;
  o.height = 300;
  const std::string p = path("saddle_K.png");
  viz::render_png(p, saddle.mesh, saddle.field, o);
  const test::PngStats s = test::png_stats(p);
  EXPECT_GT(s.bluish, 0.004);
  EXPECT_LT(s.reddish, 0.001);
}

TEST_F(VizRenderTest, AoDarkensAndGlyphsAddLines) {
  const auto torus = test::torus();
  viz::RenderOptions o;
  o.width = 480;
  o.height = 360;
  const std::string plain = path("plain.png"), ao = path("ao.png"), dirs = path("dirs.png");
  viz::render_png(plain, torus.mesh, torus.field, o);
  o.shading = viz::Shading::both;
  viz::render_png(ao, torus.mesh, torus.field, o);
  o.shading = viz::Shading::lambert;
  o.dirs = true;
  viz::render_png(dirs, torus.mesh, torus.field, o);
  const auto s_plain = test::png_stats(plain), s_ao = test::png_stats(ao), s_dirs = test::png_stats(dirs);
  EXPECT_LT(s_ao.luminance_mean, s_plain.luminance_mean - 1.0);
  EXPECT_GT(test::pixel_difference(plain, dirs), 1000);
  EXPECT_GT(s_dirs.white, s_plain.white + 0.001);
}

// A red ridge on a surface at the red end of the map stays visible: its white halo.
TEST_F(VizRenderTest, LinesStayVisibleOnTheirOwnColour) {
  const auto torus = test::torus(1.f, 0.4f);
  viz::RenderOptions o;
  o.color = "H";  // positive everywhere on this torus: all of it at the red end of the range
  o.cmap = "diverging";
  o.range = viz::ColorRange{-1e-3, 1e-3};
  o.width = 320;
  o.height = 240;
  o.title = "";
  o.view.view = NamedView::plus_z;
  lines::Polylines ridge;  // the torus's top circle, as a ridge
  for (int i = 0; i <= 96; ++i) {
    const float a = float(i) * 6.2831853f / 96;
    ridge.points.push_back({std::cos(a), std::sin(a), 0.4f});
  }
  ridge.offsets = {0, std::uint32_t(ridge.points.size())};
  ridge.type = {lines::LineType::ridge};
  ridge.strength = {1.f};
  const std::string plain = path("plain.png"), lined = path("lined.png");
  viz::render_png(plain, torus.mesh, torus.field, o);
  viz::render_png(lined, torus.mesh, torus.field, o, [&](const Camera&) { return ridge; });
  const int white[3] = {255, 255, 255};
  const double before = test::fraction_near(plain, white, 0, 0.8, 30);
  const double after = test::fraction_near(lined, white, 0, 0.8, 30);
  EXPECT_LT(before, 0.001);
  EXPECT_GT(after, before + 0.004) << "the ridge's halo is missing: red on red";
}

TEST_F(VizRenderTest, EveryQuantityRenders) {
  const auto torus = test::torus(48, 24);
  viz::RenderOptions o;
  o.width = 200;
  o.height = 150;
  for (const char* q : {"H", "K", "k1", "k2", "ShapeIndex", "Curvedness", "AO"}) {
    o.color = q;
    const std::string p = path(std::string(q) + ".png");
    viz::render_png(p, torus.mesh, torus.field, o);
    EXPECT_GT(test::png_stats(p).luminance_variance, 10.0) << q;
  }
}

TEST_F(VizRenderTest, BadRequestsAreErrorsAndLeaveNoFile) {
  const auto torus = test::torus(24, 12);
  viz::RenderOptions o;
  o.width = 200;
  o.height = 150;
  const std::string p = path("bad.png");
  o.color = "Gauss";
  EXPECT_THROW(viz::render_png(p, torus.mesh, torus.field, o), Error);
  o.color = "H";
  curvature::CurvatureField no_h = torus.field;
  no_h.H.clear();
  EXPECT_THROW(viz::render_png(p, torus.mesh, no_h, o), Error);
  EXPECT_THROW(viz::render_png(p, Mesh{}, curvature::CurvatureField{}, o), Error);
  o.width = 0;
  EXPECT_THROW(viz::render_png(p, torus.mesh, torus.field, o), Error);
  EXPECT_FALSE(fs::exists(p));
  o.width = 200;
  const std::string nowhere = path("no/such/folder/x.png");
  EXPECT_THROW(viz::render_png(nowhere, torus.mesh, torus.field, o), Error);
  EXPECT_FALSE(fs::exists(path("no")));
}

namespace {

test::Box to_box(const viz::PixelBox& b) { return {b.x0, b.y0, b.x1, b.y1}; }

/// The surface's pixels keep a margin inside its viewport (so off the title and the legend).
void expect_framed(const std::string& png, const viz::PictureLayout& l, const std::string& what) {
  // everything outside the surface's viewport is left out: the title, the legend column (the 3D
  // renderer cannot draw there), so a surface cut by the viewport shows as a missing margin
  const viz::PixelBox& v = l.surface;
  const std::vector<test::Box> skip = {{0, 0, v.x0, l.height}, {v.x1, 0, l.width, l.height},
                                       {0, 0, l.width, v.y0}, {0, v.y1, l.width, l.height}};
  const test::Box fg = test::foreground_box(png, viz::kBackgroundBottom, viz::kBackgroundTop, skip);
  ASSERT_GT(fg.x1, fg.x0) << what << ": nothing drawn";
  const viz::PixelBox& s = l.surface;
  const int mx = std::max(2, (s.x1 - s.x0) / 50), my = std::max(2, (s.y1 - s.y0) / 50);
  EXPECT_GE(fg.x0, s.x0 + mx) << what << ": left";
  EXPECT_LE(fg.x1, s.x1 - mx) << what << ": right (legend side)";
  EXPECT_GE(fg.y0, s.y0 + my) << what << ": bottom";
  EXPECT_LE(fg.y1, s.y1 - my) << what << ": top (title side)";
  // and it fills the free part reasonably: one of the two extents uses most of it
  const double fill = std::max(double(fg.x1 - fg.x0) / (s.x1 - s.x0), double(fg.y1 - fg.y0) / (s.y1 - s.y0));
  EXPECT_GT(fill, 0.6) << what;
}

/// A closed box with flat faces, the shape that ran off the edges before (the VDB cube).
test::TestSurface box_surface(float sx, float sy, float sz) {
  test::TestSurface b;
  const float x[2] = {-sx, sx}, y[2] = {-sy, sy}, z[2] = {-sz, sz};
  for (int i = 0; i < 8; ++i) b.mesh.positions.push_back({x[i & 1], y[(i >> 1) & 1], z[i >> 2]});
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    b.mesh.triangles.push_back({static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[1]),
                                static_cast<std::uint32_t>(f[2])});
    b.mesh.triangles.push_back({static_cast<std::uint32_t>(f[0]), static_cast<std::uint32_t>(f[2]),
                                static_cast<std::uint32_t>(f[3])});
  }
  const std::size_t n = b.mesh.positions.size();
  b.field.normals.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = b.mesh.positions[i];
    const float l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    b.field.normals[i] = {p[0] / l, p[1] / l, p[2] / l};
  }
  for (std::size_t i = 0; i < n; ++i) {
    test::derive(b.field, i % 2 ? 1.f : 0.f, i % 2 ? 0.f : -1.f);
    b.field.ao.push_back(1.f);
  }
  b.field.dir1.assign(n, {1, 0, 0}), b.field.dir2.assign(n, {0, 1, 0});
  return b;
}

}  // namespace

TEST_F(VizRenderTest, SurfaceKeepsAMarginAndStaysOffTitleAndLegend) {
  const auto torus = test::torus();
  const auto saddle = test::saddle();
  const auto cube = box_surface(1, 1, 1), slab = box_surface(3, 1, 0.3f), tower = box_surface(0.3f, 0.3f, 3);
  const std::vector<std::pair<std::string, const test::TestSurface*>> surfaces = {
      {"torus", &torus}, {"saddle", &saddle}, {"cube", &cube}, {"slab", &slab}, {"tower", &tower}};
  // every surface from the default view in a landscape picture; the flat and tall ones also
  // from the side in a small square and a portrait one (about ten renders in all)
  struct Case {
    std::size_t surface;
    const char* view;
    int w, h;
  };
  const std::vector<Case> cases = {{0, "iso", 640, 480}, {1, "iso", 640, 480}, {2, "iso", 640, 480},
                                   {3, "iso", 640, 480}, {4, "iso", 640, 480}, {2, "+x", 300, 300},
                                   {3, "-z", 300, 300},  {4, "+x", 360, 640},  {3, "iso", 360, 640}};
  for (const Case& c : cases) {
    const auto& [name, surface] = surfaces[c.surface];
    viz::RenderOptions o;
    o.width = c.w;
    o.height = c.h;
    o.view.view = parse_named_view(c.view);
    o.title = name + std::string(" seen from ") + c.view + ", a title of some length";
    const std::string p = path(name + "_" + c.view + "_" + std::to_string(c.w) + ".png");
    const viz::PictureLayout l = viz::render_png(p, surface->mesh, surface->field, o);
    expect_framed(p, l, p);
  }
}

TEST_F(VizRenderTest, AoMapIsGrey) {
  const auto torus = test::torus();
  viz::RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.color = "AO";
  const std::string p = path("ao.png");
  const viz::PictureLayout l = viz::render_png(p, torus.mesh, torus.field, o);
  const test::MaskedStats m =
      test::surface_stats(p, to_box(l.surface), viz::kBackgroundBottom, viz::kBackgroundTop);
  ASSERT_GT(m.count, 1000);
  EXPECT_LT(m.chroma, 6.0) << "AO is drawn in grey";
  o.color = "H";
  viz::render_png(p, torus.mesh, torus.field, o);
  EXPECT_GT(test::surface_stats(p, to_box(l.surface), viz::kBackgroundBottom, viz::kBackgroundTop).chroma, 15.0)
      << "H is drawn in colour";
}

TEST_F(VizRenderTest, AmbientAoShadesTheAmbientTermOnly) {
  // With AO = 0 everywhere, --shading ambient-ao removes only the ambient light: the diffuse
  // light stays (Griffin et al.'s S+L), where 'both' darkens everything.
  auto torus = test::torus();
  viz::RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.color = "ShapeIndex";
  auto mean_luminance = [&](float ao, viz::Shading shading, const std::string& name) {
    torus.field.ao.assign(torus.field.ao.size(), ao);
    o.shading = shading;
    const std::string p = path(name);
    const viz::PictureLayout l = viz::render_png(p, torus.mesh, torus.field, o);
    const auto m = test::surface_stats(p, to_box(l.surface), viz::kBackgroundBottom, viz::kBackgroundTop, 4);
    EXPECT_GT(m.count, 1000) << name;
    return m.luminance;
  };
  const double open = mean_luminance(1.f, viz::Shading::ambient_ao, "open.png");
  const double closed = mean_luminance(0.f, viz::Shading::ambient_ao, "closed.png");
  const double both = mean_luminance(0.f, viz::Shading::both, "both.png");
  const double lambert = mean_luminance(0.f, viz::Shading::lambert, "lambert.png");
  EXPECT_GT(closed, 0.3 * open) << "the diffuse light is kept";
  EXPECT_LT(closed, 0.95 * open) << "AO changes the ambient term";
  EXPECT_LT(both, 0.3 * open) << "'both' darkens the whole colour";
  EXPECT_GT(lambert, closed) << "lambert ignores AO";
}

TEST_F(VizRenderTest, UnmeasuredVerticesGetTheNoDataColourAndStayOutOfTheRange) {
  // A torus whose outer half the estimator could not measure (flagged Unreliable, placeholder
  // zero curvature), with 4% measured spikes (radius under half an edge, as slivers give): enough
  // to set a p99 range by themselves.
  auto torus = test::torus(1.f, 0.4f);
  auto& f = torus.field;
  const std::size_t n = f.H.size();
  f.unreliable.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (torus.mesh.positions[i][0] > 0.6f) {
      f.unreliable[i] = 1;
      f.k1[i] = f.k2[i] = f.H[i] = f.K[i] = 0;
    }
  for (std::size_t i = 7; i < n; i += 23)
    if (!f.unreliable[i]) f.k1[i] = f.H[i] = 1e4f;
  viz::RenderOptions o;
  o.color = "H";
  o.width = 640;
  o.height = 480;
  viz::CurvatureScene scene;
  scene.set_options(o);
  scene.set_surface(torus.mesh, f);
  // The range is that of the counted vertices alone: H of the measured torus lies in
  // [1/(2r) - ..., 1/r], so with the spikes or the zeros counted it would reach 1e4 or 0.
  EXPECT_GT(scene.range_hi(), 1.0) << "the range lost the measured vertices";
  EXPECT_LT(scene.range_hi(), 3.0) << "a spike or an unmeasured vertex set the range";
  const int yellow[3] = {255, 217, 0};
  const std::string with = path("unmeasured.png");
  viz::render_png(with, torus.mesh, f, o);
  EXPECT_GT(test::fraction_near(with, yellow), 0.01) << "unmeasured vertices are not drawn in the no-data colour";
  EXPECT_GT(test::fraction_near(with, yellow, 0.8, 1.0), 0.0005) << "no no-data swatch in the legend";
  const std::string without = path("measured.png");
  f.unreliable.assign(n, 0);
  viz::render_png(without, torus.mesh, f, o);
  EXPECT_LT(test::fraction_near(without, yellow), 0.001) << "the no-data colour where every vertex is measured";
  EXPECT_EQ(test::fraction_near(without, yellow, 0.8, 1.0), 0) << "a no-data swatch with nothing unmeasured";
}

// A label map gets a colour per label, neighbours distinct (a ramp made labels 12 and 13 look
// alike), and a legend that lists the labels instead of a bar with ticks at 12.8, 13.5.
TEST_F(VizRenderTest, LabelsGetDistinctColoursAndALegendOfTheirValues) {
  auto torus = test::torus(1.f, 0.4f);
  const std::size_t n = torus.mesh.positions.size();
  std::vector<float> label(n);
  for (std::size_t i = 0; i < n; ++i)  // four labels by quadrant: 12, 13, 14, 15
    label[i] = 12.f + float(torus.mesh.positions[i][0] > 0) + 2.f * float(torus.mesh.positions[i][1] > 0);
  torus.field.extra.push_back({"Label", label});
  viz::RenderOptions o;
  o.color = "Label";
  o.width = 640;
  o.height = 480;
  viz::CurvatureScene scene;
  scene.set_options(o);
  scene.set_surface(torus.mesh, torus.field);
  const viz::PictureLayout& l = scene.layout();
  ASSERT_EQ(l.swatches.size(), 4u) << "one swatch per label";
  ASSERT_EQ(l.labels.size(), 4u);
  EXPECT_EQ(l.labels[0].text, "12");
  EXPECT_EQ(l.labels[3].text, "15");
  EXPECT_TRUE(l.bar.empty()) << "no colour bar for labels";
  for (std::size_t i = 1; i < 4; ++i) {
    const auto a = viz::categorical_color(i - 1), b = viz::categorical_color(i);
    double d = 0;
    for (int c = 0; c < 3; ++c) d += (a[c] - b[c]) * (a[c] - b[c]);
    EXPECT_GT(std::sqrt(d), 0.25) << "labels " << i - 1 << " and " << i << " look alike";
  }
  // Each label's colour is on the picture (it is a real drawn legend and surface).
  const std::string png = path("labels.png");
  viz::render_png(png, torus.mesh, torus.field, o);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto c = viz::categorical_color(i);
    const int rgb[3] = {int(255 * c[0] + 0.5), int(255 * c[1] + 0.5), int(255 * c[2] + 0.5)};
    EXPECT_GT(test::fraction_near(png, rgb, 0.8, 1.0), 0.0) << "no swatch of label " << 12 + i;
  }
}

// The surface's box, hence the camera, does not change when only the coloured array does.
TEST_F(VizRenderTest, ColouringAnotherArrayKeepsTheFraming) {
  auto torus = test::torus(1.f, 0.4f);
  torus.field.extra.push_back({"Label", std::vector<float>(torus.mesh.positions.size(), 123456.f)});
  viz::RenderOptions o;
  o.width = 800;
  o.height = 600;
  viz::CurvatureScene scene;
  scene.set_surface(torus.mesh, torus.field);
  std::vector<viz::PixelBox> boxes;
  for (const char* q : {"H", "K", "ShapeIndex", "Curvedness", "AO", "Label"}) {
    o.color = q;
    scene.set_options(o);
    boxes.push_back(scene.layout().surface);
  }
  for (std::size_t i = 1; i < boxes.size(); ++i) {
    EXPECT_EQ(boxes[i].x1, boxes[0].x1) << i;
    EXPECT_EQ(boxes[i].y1, boxes[0].y1) << i;
  }
}
