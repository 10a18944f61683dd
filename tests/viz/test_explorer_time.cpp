// The explorer's time slider and play/pause (space) for a time series, driven by a script.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "explorer_fixture.h"
#include "png_stats.h"
#include "viz/explorer.h"

namespace fs = std::filesystem;
using namespace isocurv;

namespace {

/// A series of tori whose tube radius grows with the frame; `frame` is the one set_frame made
/// current, and every surface call is recorded as (frame, isovalue).
struct TorusSeries {
  int frame = 0;
  std::vector<std::pair<int, float>> calls;
  std::vector<int> set_calls;
};

}  // namespace

class VizExplorerTime : public test::ExplorerTest {
 protected:
  /// torus_setup's explorer as a series of `frames` tori (frame 3 fails to load), played at 50
  /// frames a second, recorded in `ts`.
  viz::ExplorerSetup series_setup(int frames) {
    viz::ExplorerSetup setup = torus_setup(0.3f, 480, 360);
    setup.frames = frames;
    setup.play_fps = 50;
    setup.set_frame = [this](int k) {
      ts.set_calls.push_back(k);
      if (k == 3) throw Error("frame 3 is broken");
      ts.frame = k;
    };
    setup.frame_label = [](int k) { return "torus_" + std::to_string(k); };
    setup.surface = [this](float iso) {
      ts.calls.emplace_back(ts.frame, iso);
      return test::torus_surface(iso * (1 + 0.3f * ts.frame), 64, 32, "");
    };
    return setup;
  }
  TorusSeries ts;
};

TEST_F(VizExplorerTime, TimeSliderReextractsAtTheCurrentIsovalue) {
  viz::ExplorerSetup setup = series_setup(5);
  const std::string f0 = file("f0.png"), f2 = file("f2.png"),
                    bad = file("bad.png");  // the status line names the failure
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(f0), A::set_isovalue(0.35f), A::set_frame(2),
                  A::screenshot(f2), A::set_frame(3),        A::screenshot(bad)};
  viz::run_explorer(setup);
  // Frame 0 at 0.3, frame 0 at 0.35 (the slider), frame 2 at 0.35; frame 3 fails and 2 stays.
  ASSERT_GE(ts.calls.size(), 3u);
  EXPECT_EQ(ts.calls[0], std::make_pair(0, 0.3f));
  EXPECT_EQ(ts.calls[1], std::make_pair(0, 0.35f));
  EXPECT_EQ(ts.calls[2], std::make_pair(2, 0.35f)) << "a new frame is cut at the current isovalue";
  EXPECT_EQ(ts.calls.size(), 3u) << "the broken frame must not reach the surface callback";
  EXPECT_EQ(ts.set_calls, (std::vector<int>{2, 3, 2}))
      << "after a failure the shown frame is made current again";
  EXPECT_GT(test::pixel_difference(f0, f2), 2000) << "the frame change did not change the image";
}

TEST_F(VizExplorerTime, SpacePlaysAndPauses) {
  viz::ExplorerSetup setup = series_setup(3);  // frames 0, 1, 2: never the broken 3
  using A = viz::ExplorerAction;
  setup.script = {A::press(' ')};
  for (int i = 0; i < 8; ++i) setup.script.push_back(A::press('c'));  // ~0.8 s of play
  setup.script.push_back(A::press(' '));
  viz::run_explorer(setup);
  // While playing (about 800 ms at up to 50 frames a second) frames advance and wrap around.
  ASSERT_GE(ts.set_calls.size(), 2u) << "space did not play";
  for (std::size_t i = 0; i < ts.set_calls.size(); ++i)
    EXPECT_EQ(ts.set_calls[i], int((i + 1) % 3));
  const std::size_t after_pause = ts.set_calls.size();
  EXPECT_LE(after_pause, 60u);
}

TEST_F(VizExplorerTime, OneFrameHasNoTimeSlider) {
  viz::ExplorerSetup setup = series_setup(1);
  using A = viz::ExplorerAction;
  setup.script = {A::set_frame(2), A::press(' ')};
  viz::run_explorer(setup);
  EXPECT_TRUE(ts.set_calls.empty());
  EXPECT_EQ(ts.calls.size(), 1u);
}

// A series of meshes (ExplorerSetup::has_isovalue false, as `isocurv view --time-series` of mesh
// files): no isovalue, the status line names the frame, and with shared_color_range every frame
// is coloured over the first frame's range (the legend does not change from frame to frame).
class VizExplorerMeshSeries : public test::ExplorerTest {
 protected:
  /// Three tori, tube radius 0.2, 0.3, 0.4 (H from about 2.5 down to 1.3), as a mesh series.
  viz::ExplorerSetup mesh_series(bool shared) {
    viz::ExplorerSetup setup = torus_setup(0.3f, 480, 360);
    setup.has_isovalue = false;
    setup.min_value = setup.max_value = 0;  // not used without an isovalue
    setup.shared_color_range = shared;
    setup.frames = 3;
    setup.set_frame = [this](int k) { frame = k; };
    setup.frame_label = [](int k) { return "torus_" + std::to_string(k) + ".vtp"; };
    setup.surface = [this](float iso) {
      extracted.push_back(iso);
      return test::torus_surface(0.2f + 0.1f * frame, 64, 32, "mesh");
    };
    return setup;
  }
  int frame = 0;
};

TEST_F(VizExplorerMeshSeries, NoIsovalueAndTheFirstFramesColourRange) {
  viz::ExplorerSetup setup = mesh_series(true);
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(file("f0.png")), A::status(file("s0.txt")),
                  A::set_isovalue(0.5f),  // no slider: nothing happens
                  A::press('i'),          A::status(file("i.txt")),
                  A::set_frame(2),        A::screenshot(file("f2.png")),
                  A::status(file("s2.txt"))};
  viz::run_explorer(setup);
  EXPECT_EQ(extracted.size(), 2u) << "frame 0, then frame 2; the isovalue moves nothing";
  const std::string s0 = test::read_text(file("s0.txt")), s2 = test::read_text(file("s2.txt"));
  EXPECT_NE(s0.find("mesh of frame 0"), std::string::npos) << s0;
  EXPECT_EQ(s0.find("isovalue"), std::string::npos) << "no isovalue for meshes:\n" << s0;
  EXPECT_NE(s0.find("frame 0 of 3 (torus_0.vtp)"), std::string::npos) << s0;
  EXPECT_NE(s2.find("frame 2 of 3 (torus_2.vtp)"), std::string::npos) << s2;
  EXPECT_NE(test::read_text(file("i.txt")).find("no isovalue here"), std::string::npos);
  EXPECT_GT(test::pixel_difference(file("f0.png"), file("f2.png")), 2000) << "frame 2 not shown";
  EXPECT_EQ(test::legend_difference(file("f0.png"), file("f2.png"), 0.88, 0.4), 0)
      << "the colour range changed from frame 0 to frame 2";
}

TEST_F(VizExplorerMeshSeries, WithoutSharedRangesEachFrameHasItsOwn) {
  viz::ExplorerSetup setup = mesh_series(false);
  using A = viz::ExplorerAction;
  setup.script = {A::screenshot(file("f0.png")), A::set_frame(2), A::screenshot(file("f2.png"))};
  viz::run_explorer(setup);
  EXPECT_GT(test::legend_difference(file("f0.png"), file("f2.png"), 0.88, 0.4), 100)
      << "the legend should follow each frame's own range (else the test above proves nothing)";
}

TEST_F(VizExplorerMeshSeries, ScreenSpaceRasterisesEachFramesMesh) {
  viz::ExplorerSetup setup = mesh_series(true);
  std::vector<int> cast_frames;  // the frame current at each cast of a mesh
  setup.screen.image = [&](float, const viz::Surface* mesh, const Camera&, int w, int h) {
    if (!mesh) throw Error("a mesh series has no volume to cast");
    cast_frames.push_back(frame);
    viz::ScreenImage img;
    img.width = w, img.height = h;
    img.H.assign(img.pixels(), 1.f), img.K.assign(img.pixels(), 1.f);
    img.valid.assign(img.pixels(), 1);
    return img;
  };
  using A = viz::ExplorerAction;
  setup.script = {A::press('x'), A::set_frame(1), A::status(file("s.txt")), A::press('x')};
  viz::run_explorer(setup);
  ASSERT_FALSE(cast_frames.empty()) << "'x' cast nothing";
  EXPECT_EQ(cast_frames.front(), 0);
  EXPECT_EQ(cast_frames.back(), 1) << "a new frame is rasterised in screen-space mode";
  EXPECT_NE(test::read_text(file("s.txt")).find("screen space: on"), std::string::npos);
}
