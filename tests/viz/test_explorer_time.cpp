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
