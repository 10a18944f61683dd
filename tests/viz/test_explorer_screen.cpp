// The explorer's screen-space mode ('x'), driven by a script under a private Xvfb: the slider
// re-casts instead of re-extracting, camera moves re-cast, 'c' alternates H and K, and leaving
// the mode extracts the isovalue reached. The image callback is a stand-in (a disc whose H grows
// with the isovalue), so only the explorer is tested here; tests/app runs the real cast.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "explorer_fixture.h"
#include "png_stats.h"
#include "viz/curvature_scene.h"
#include "viz/explorer.h"

namespace fs = std::filesystem;
using namespace isocurv;

namespace {

struct Cast {
  float iso = 0;
  bool of_mesh = false;
  Camera camera;
  int width = 0, height = 0;
};

/// A centred disc of radius 0.3 min(width, height): H = iso (1 + x / width) > 0, K = -H^2 < 0;
/// outside it nothing is valid.
viz::ScreenImage disc_image(float iso, int w, int h) {
  viz::ScreenImage img;
  img.width = w, img.height = h;
  img.H.assign(img.pixels(), 0.f), img.K.assign(img.pixels(), 0.f);
  img.valid.assign(img.pixels(), 0);
  const double r = 0.3 * std::min(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = x + 0.5 - 0.5 * w, dy = y + 0.5 - 0.5 * h;
      if (dx * dx + dy * dy > r * r) continue;
      const std::size_t i = std::size_t(x) + std::size_t(w) * y;
      img.H[i] = iso * float(1 + double(x) / w);
      img.K[i] = -img.H[i] * img.H[i];
      img.valid[i] = 1;
    }
  img.detail = "stand-in disc";
  return img;
}

bool same(const Camera& a, const Camera& b) {
  return a.position == b.position && a.focal_point == b.focal_point && a.view_up == b.view_up;
}

}  // namespace

class VizExplorerScreen : public test::ExplorerTest {};

TEST_F(VizExplorerScreen, SliderReCastsAndLeavingExtractsTheIsovalueReached) {
  std::vector<Cast> casts;
  viz::ExplorerSetup setup = torus_setup(0.25f, 640, 480);
  setup.view.color = "ShapeIndex";  // screen-space mode switches to H
  setup.screen.image = [&](float iso, const viz::Surface* mesh, const Camera& cam, int w, int h) {
    casts.push_back({iso, mesh != nullptr, cam, w, h});
    return disc_image(iso, w, h);
  };
  const std::string mesh_png = file("mesh.png"), h_png = file("h.png"), h2_png = file("h2.png"),
                    k_png = file("k.png"), back_png = file("back.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(mesh_png), A::press('x'),         A::screenshot(h_png),
                  A::set_isovalue(0.5f),   A::screenshot(h2_png), A::press('c'),
                  A::screenshot(k_png),    A::press('v'),         A::press('x'),
                  A::screenshot(back_png)};
  viz::run_explorer(setup);

  ASSERT_EQ(extracted.size(), 2u) << "the slider in screen-space mode must not extract";
  EXPECT_FLOAT_EQ(extracted[0], 0.25f);
  EXPECT_FLOAT_EQ(extracted[1], 0.5f) << "leaving the mode extracts the isovalue reached";
  ASSERT_GE(casts.size(), 3u);
  EXPECT_FLOAT_EQ(casts.front().iso, 0.25f);
  EXPECT_FLOAT_EQ(casts.back().iso, 0.5f);
  bool moved = false;
  for (std::size_t i = 1; i < casts.size(); ++i) {
    EXPECT_FALSE(casts[i].of_mesh) << "the volume's surface is cast, not a mesh";
    EXPECT_EQ(casts[i].width, casts[0].width) << "the surface box does not follow the values";
    EXPECT_EQ(casts[i].height, casts[0].height);
    moved = moved || !same(casts[i].camera, casts[i - 1].camera);
  }
  EXPECT_TRUE(moved) << "'v' moved the camera, which must re-cast";
  EXPECT_GT(casts[0].width, 300);
  EXPECT_LT(casts[0].width, 640) << "the image fills the surface part, beside the legend";

  for (const std::string& p : {mesh_png, h_png, h2_png, k_png, back_png})
    ASSERT_TRUE(fs::exists(p)) << p;
  EXPECT_GT(test::pixel_difference(mesh_png, h_png), 5000) << "'x' did not show the image";
  EXPECT_GT(test::png_stats(h_png).reddish, 0.05) << "positive H is red";
  EXPECT_LT(test::png_stats(h_png).bluish, 0.005);
  EXPECT_GT(test::png_stats(k_png).bluish, 0.05) << "'c' shows K, negative: blue";
  // The disc, not its box: pixels outside it are transparent and show the background.
  const test::Box fg = test::foreground_box(
      h_png, viz::kBackgroundBottom, viz::kBackgroundTop,
      std::vector<test::Box>{{int(0.75 * 640), 0, 640, 480}, {0, 0, 640, 110}, {0, 440, 640, 480}});
  const int side = fg.x1 - fg.x0, tall = fg.y1 - fg.y0;
  EXPECT_NEAR(side, 0.6 * std::min(casts[0].width, casts[0].height), 6)
      << "the foreground is the disc";
  EXPECT_NEAR(tall, side, 6);
}

TEST_F(VizExplorerScreen, StartsWithoutExtractingAndRasterisesAnOpenedMesh) {
  int framed = 0;
  std::vector<Cast> casts;
  viz::ExplorerSetup setup = torus_setup(0.3f, 480, 360);
  setup.open_mesh = [&](const std::string&) { return test::torus_surface(0.2f, 64, 32, "opened"); };
  setup.screen.start_on = true;
  setup.screen.bounds = [&](float, std::array<double, 6>& b) {
    ++framed;
    b = {-1.4, 1.4, -1.4, 1.4, -0.4, 0.4};
    return true;
  };
  setup.screen.image = [&](float iso, const viz::Surface* mesh, const Camera& cam, int w, int h) {
    if (iso > 0.55f) throw Error("stand-in failure");
    casts.push_back({iso, mesh != nullptr, cam, w, h});
    return disc_image(iso, w, h);
  };
  const std::string first = file("first.png"), failed = file("failed.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(first),  A::set_isovalue(0.4f), A::set_isovalue(0.58f),
                  A::screenshot(failed), A::press('o'),         A::type("torus.ply\r")};
  viz::run_explorer(setup);

  EXPECT_TRUE(extracted.empty()) << "screen-space mode from the start extracts nothing";
  EXPECT_GE(framed, 1) << "the camera is framed on the volume's surface box";
  ASSERT_GE(casts.size(), 3u);
  EXPECT_FLOAT_EQ(casts[0].iso, 0.3f);
  EXPECT_FALSE(casts[0].of_mesh);
  EXPECT_FLOAT_EQ(casts[1].iso, 0.4f);
  EXPECT_TRUE(casts.back().of_mesh) << "the opened mesh is rasterised";
  ASSERT_TRUE(fs::exists(failed));
  EXPECT_GT(test::png_stats(failed).reddish, 0.03) << "a failed cast keeps the previous image";
}

TEST_F(VizExplorerScreen, ASlowCastIsCoarseWhileTheSliderIsDraggedAndFullOnRelease) {
  std::vector<Cast> casts;
  viz::ExplorerSetup setup = torus_setup(0.3f, 480, 360);
  setup.screen.start_on = true;
  setup.screen.image = [&](float iso, const viz::Surface* mesh, const Camera& cam, int w, int h) {
    casts.push_back({iso, mesh != nullptr, cam, w, h});
    viz::ScreenImage img = disc_image(iso, w, h);
    img.update_ms = 400;  // as if slow: between 1 and 4 live-update limits, so 1/2 while dragging
    return img;
  };
  using A = viz::ExplorerAction;
  setup.script = {A::set_isovalue(0.45f)};  // moves the slider (live), then releases it
  viz::run_explorer(setup);
  ASSERT_GE(casts.size(), 3u);
  const Cast& first = casts.front();
  const Cast& dragged = casts[casts.size() - 2];
  const Cast& released = casts.back();
  EXPECT_FLOAT_EQ(dragged.iso, 0.45f);
  EXPECT_EQ(dragged.width, (first.width + 1) / 2) << "half resolution while dragging";
  EXPECT_FLOAT_EQ(released.iso, 0.45f);
  EXPECT_EQ(released.width, first.width) << "full resolution on release";
  EXPECT_EQ(released.height, first.height);
}

TEST(VizScene, ImageModeChecksItsInput) {
  viz::CurvatureScene scene;
  viz::RenderOptions o;
  o.color = "Curvedness";
  scene.set_options(o);
  EXPECT_THROW(scene.set_image_mode(true), Error) << "only H and K have screen-space images";
  o.color = "K";
  scene.set_options(o);
  scene.set_image_mode(true);
  viz::ScreenImage img = disc_image(0.3f, 40, 30);
  img.K.clear();  // Mellado gives none
  EXPECT_THROW(scene.set_image(img), Error);
  img = disc_image(0.3f, 40, 30);
  img.valid.pop_back();
  EXPECT_THROW(scene.set_image(img), Error);
  EXPECT_THROW(scene.set_image(disc_image(0.3f, 40, 30), 0), Error);
  scene.set_image(disc_image(0.3f, 40, 30));
  EXPECT_LT(scene.range_lo(), 0) << "the legend spans the image's K";
  EXPECT_TRUE(scene.image_mode());
}
