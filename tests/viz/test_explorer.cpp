// viz::run_explorer driven by a script under a private Xvfb when there is no display.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "explorer_fixture.h"
#include "lines/polylines.h"
#include "lines/reference.h"
#include "png_stats.h"
#include "viz/camera_file.h"
#include "viz/explorer.h"
#include "viz/quantity.h"

namespace fs = std::filesystem;
using namespace isocurv;

class VizExplorer : public test::ExplorerTest {};
class VizCameraFile : public test::ExplorerTest {};

TEST_F(VizExplorer, ScriptedSliderMoveAndKeysChangeTheImage) {
  viz::ExplorerSetup setup = torus_setup(0.25f, 640, 480);
  setup.view.title = "scripted explorer";
  setup.screenshot_prefix = file("shot");
  const std::string before = file("before.png"), after = file("after.png"),
                    colour = file("colour.png"), glyphs = file("glyphs.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(before), A::set_isovalue(0.5f), A::screenshot(after),
                  A::press('c'),         A::screenshot(colour), A::press('d'),
                  A::screenshot(glyphs), A::press('s')};
  viz::run_explorer(setup);

  ASSERT_EQ(extracted.size(), 2u);
  EXPECT_FLOAT_EQ(extracted[0], 0.25f);
  EXPECT_FLOAT_EQ(extracted[1], 0.5f);
  for (const std::string& p : {before, after, colour, glyphs}) {
    ASSERT_TRUE(fs::exists(p)) << p;
    const auto s = test::png_stats(p);
    EXPECT_EQ(s.width, 640);
    EXPECT_EQ(s.height, 480);
    EXPECT_GT(s.luminance_variance, 100.0) << p;
  }
  EXPECT_GT(test::pixel_difference(before, after), 5000)
      << "slider move did not change the surface";
  EXPECT_GT(test::pixel_difference(after, colour), 5000) << "'c' did not recolour";
  EXPECT_GT(test::pixel_difference(colour, glyphs), 1000) << "'d' did not draw glyphs";
  EXPECT_GT(test::png_stats(colour).bluish, 0.005) << "K on a torus has a negative part";
  EXPECT_TRUE(fs::exists(dir / "shot-001.png")) << "'s' saves <prefix>-001.png";
}

TEST_F(VizExplorer, ColourKeyReachesTheSurfacesExtraArrays) {
  viz::ExplorerSetup setup = torus_setup(0.4f, 480, 360);
  // A torus carrying one extra array (as `features` writes): its x coordinate, a left-right ramp
  // that the sequential (viridis) map shows in greens the diverging map never has.
  auto make = [](float iso) {
    auto t = test::torus(1.f, iso, 64, 32);
    std::vector<float> ramp(t.mesh.positions.size());
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = t.mesh.positions[i][0];
    t.field.extra.push_back({"LBE_r0.3", ramp});
    return t;
  };
  setup.surface = [&](float iso) {
    auto t = make(iso);
    return viz::Surface{std::move(t.mesh), std::move(t.field), 0, "torus with an extra array"};
  };
  const std::vector<std::string> names = viz::field_quantities(make(0.4f).field);
  const auto at = [&](const std::string& n) {
    return std::find(names.begin(), names.end(), n) - names.begin();
  };
  ASSERT_LT(at("LBE_r0.3"), static_cast<long>(names.size())) << "the extra array is listed";
  const long presses = at("LBE_r0.3") - at("H");  // the explorer starts on H
  ASSERT_GT(presses, 0);
  const std::string h = file("h.png"), extra = file("extra.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(h)};
  for (long i = 0; i < presses; ++i) setup.script.push_back(A::press('c'));
  setup.script.push_back(A::screenshot(extra));
  viz::run_explorer(setup);
  ASSERT_TRUE(fs::exists(h) && fs::exists(extra));
  EXPECT_LT(test::png_stats(h).greenish, 0.002) << "H is drawn with the diverging map";
  EXPECT_GT(test::png_stats(extra).greenish, 0.01) << "'c' did not reach the extra array";
}

TEST_F(VizExplorer, FailedUpdateKeepsThePreviousSurface) {
  int calls = 0;
  viz::ExplorerSetup setup = torus_setup(0.3f, 320, 240);
  setup.min_value = 0.f;
  setup.max_value = 1.f;
  setup.surface = [&](float iso) -> viz::Surface {
    ++calls;
    if (iso > 0.5f) throw Error("synthetic", "no surface at this isovalue");
    return test::torus_surface(iso, 32, 16, "");
  };
  const std::string before = file("before.png"), after = file("after.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(before), A::set_isovalue(0.9f), A::screenshot(after)};
  viz::run_explorer(setup);
  EXPECT_EQ(calls, 2);
  ASSERT_TRUE(fs::exists(after));
  // only the status line changes (it reports the error); the surface stays
  const long differ = test::pixel_difference(before, after);
  EXPECT_GT(differ, 0);
  EXPECT_LT(differ, 320 * 240 * 3 / 4);
}

TEST_F(VizExplorer, BadSetupIsAnError) {
  viz::ExplorerSetup setup;
  EXPECT_THROW(viz::run_explorer(setup), Error);  // no callback
  setup.surface = [](float) { return viz::Surface{}; };
  setup.min_value = 1;
  setup.max_value = 0;
  EXPECT_THROW(viz::run_explorer(setup), Error);
  setup.min_value = 0;
  setup.max_value = 1;
  setup.isovalue = 2;
  EXPECT_THROW(viz::run_explorer(setup), Error);
}

TEST_F(VizExplorer, TypedIsovalueOpenSaveCameraViewsAndResize) {
  std::vector<std::string> opened, saved;
  viz::ExplorerSetup setup = torus_setup(0.25f, 400, 300, 48, 24);
  setup.camera_path = file("camera.json");
  setup.surface_path = file("surface.vtp");
  setup.title_for = [](float iso, const std::string& q) {
    return q + " at " + std::to_string(iso);
  };
  setup.open_mesh = [&](const std::string& path) {
    opened.push_back(path);
    auto s = test::saddle(32);
    return viz::Surface{std::move(s.mesh), std::move(s.field), 0, "opened"};
  };
  setup.save_surface = [&](const std::string& path, const Mesh& mesh,
                           const curvature::CurvatureField& field) {
    EXPECT_EQ(field.H.size(), mesh.positions.size());
    saved.push_back(path);
  };
  const std::string iso = file("iso.png"), side = file("side.png"), mesh = file("mesh.png"),
                    big = file("big.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(iso),  A::press('i'),
                  A::type("0.4x"),     A::press(8),
                  A::press('\r'),  // typed, one typo deleted
                  A::press('i'),       A::type("7"),
                  A::press('\r'),                            // outside the range: refused
                  A::press('v'),       A::screenshot(side),  // the +x view
                  A::press('k'),                             // camera saved
                  A::press('w'),       A::press('\r'),       // saved at surface_path
                  A::press('i'),       A::type("0.3"),
                  A::press(27),  // Escape: nothing
                  A::press('o'),       A::type("elsewhere.ply"),
                  A::press('\r'),      A::screenshot(mesh),
                  A::resize(640, 360), A::screenshot(big)};
  viz::run_explorer(setup);

  ASSERT_EQ(extracted.size(), 2u);
  EXPECT_FLOAT_EQ(extracted[1], 0.4f) << "the typed isovalue was used";
  EXPECT_EQ(saved, std::vector<std::string>{setup.surface_path});
  EXPECT_EQ(opened, std::vector<std::string>{"elsewhere.ply"});
  ASSERT_TRUE(fs::exists(setup.camera_path));
  const Camera cam = viz::load_camera(setup.camera_path);
  EXPECT_GT(cam.toward_camera()[0], 0.99) << "'v' moved to the +x view, and 'k' saved it";
  EXPECT_GT(test::pixel_difference(iso, side), 3000);
  EXPECT_GT(test::pixel_difference(side, mesh), 3000) << "the opened mesh is shown";
  ASSERT_TRUE(fs::exists(big));
  EXPECT_EQ(test::png_stats(big).width, 640);
}

TEST_F(VizCameraFile, RoundTripAndBadFiles) {
  Camera cam;
  cam.position = {1, 2, 3};
  cam.focal_point = {0, 0.5, 0};
  cam.view_up = {0, 0, 1};
  cam.ortho = true;
  cam.parallel_scale = 2.5;
  const std::string p = (dir / "c.json").string();
  // view_up is kept perpendicular to the view direction
  viz::save_camera(p, cam);
  const Camera back = viz::load_camera(p);
  EXPECT_EQ(back.position, cam.position);
  EXPECT_EQ(back.focal_point, cam.focal_point);
  EXPECT_TRUE(back.ortho);
  EXPECT_DOUBLE_EQ(back.parallel_scale, 2.5);
  const auto d = back.toward_camera();
  EXPECT_NEAR(d[0] * back.view_up[0] + d[1] * back.view_up[1] + d[2] * back.view_up[2], 0.0, 1e-12);
  for (
      const char* bad :
      {"", "[1, 2]", R"({"position": [0, 0, 1]})",
       R"({"position": [0, 0, 1], "focal_point": [0, 0, 0], "view_up": [0, 0, 1]})",
       R"({"position": [0, 0, 1], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "view_angle_deg": 200})",
       R"({"position": [0, 0, "a"], "focal_point": [0, 0, 0], "view_up": [0, 1, 0]})"}) {
    const std::string b = (dir / "bad.json").string();
    std::ofstream(b) << bad;
    EXPECT_THROW(viz::load_camera(b), Error) << bad;
  }
  EXPECT_THROW(viz::load_camera((dir / "missing.json").string()), Error);
}

TEST_F(VizExplorer, LinesKeyDrawsLinesThatFollowSurfaceAndCamera) {
  viz::ExplorerSetup setup = torus_setup(0.3f, 480, 360);
  std::vector<bool> changed;  // surface_changed of each lines call
  setup.lines = [&](const viz::Surface& s, const Camera& cam, bool surface_changed) {
    changed.push_back(surface_changed);
    lines::Options o;
    o.lines = lines::parse_line_selection("contours");
    return lines::join_segments(lines::extract_reference(s.mesh, s.field, cam, o));
  };
  const std::string off = file("off.png"), on = file("on.png"), iso = file("iso.png");
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(off), A::press('l'), A::screenshot(on), A::set_isovalue(0.45f),
                  A::screenshot(iso), A::press('r'), A::press('l'),     A::press('l')};
  viz::run_explorer(setup);
  ASSERT_GE(changed.size(), 2u);
  EXPECT_TRUE(changed[0]);  // first lines: a new surface
  EXPECT_NE(std::find(changed.begin() + 1, changed.end(), true),
            changed.end());  // the slider moved
  EXPECT_NE(std::find(changed.begin() + 1, changed.end(), false), changed.end())
      << "'r' moved the camera";
  EXPECT_GT(test::pixel_difference(off, on), 300) << "'l' drew no lines";
  EXPECT_GT(test::pixel_difference(on, iso), 1000);
}
