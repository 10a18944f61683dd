// viz::render_png under a private Xvfb when there is no display.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "png_stats.h"
#include "test_surfaces.h"
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
  EXPECT_GT(s.bluish, 0.01);
  EXPECT_LT(s.reddish, 0.001);
}

TEST_F(VizRenderTest, AoDarkensAndGlyphsAddLines) {
  const auto torus = test::torus();
  viz::RenderOptions o;
  o.width = 480;
  o.height = 360;
  const std::string plain = path("plain.png"), ao = path("ao.png"), dirs = path("dirs.png");
  viz::render_png(plain, torus.mesh, torus.field, o);
  o.ao = true;
  viz::render_png(ao, torus.mesh, torus.field, o);
  o.ao = false;
  o.dirs = true;
  viz::render_png(dirs, torus.mesh, torus.field, o);
  const auto s_plain = test::png_stats(plain), s_ao = test::png_stats(ao), s_dirs = test::png_stats(dirs);
  EXPECT_LT(s_ao.luminance_mean, s_plain.luminance_mean - 1.0);
  EXPECT_GT(test::pixel_difference(plain, dirs), 1000);
  EXPECT_GT(s_dirs.white, s_plain.white + 0.001);
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
