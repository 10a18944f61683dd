// `isocurv view --time-series` end to end: the real executable and its explorer in a real window
// on a private Xvfb (DISPLAY unset: the scripted explorer starts one), driven by a script (the
// hidden --script, viz/explorer_script.h) that moves the time slider, plays and pauses, takes
// screenshots and writes the status line's text, on a short series of volumes and of meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "explorer_fixture.h"
#include "io/mesh_file.h"
#include "io/pvd_collection.h"
#include "png_stats.h"
#include "tests/app/cli.h"
#include "viz/explorer_script.h"

namespace fs = std::filesystem;
using namespace isocurv;

class VizExplorerView : public test::ExplorerTest {
 protected:
  /// The script every test runs: frame 0, frame 2, then space twice (play, pause).
  std::string write_script() {
    const std::string path = file("script.txt");
    std::ofstream(path) << "# isocurv view --script\n"
                        << "status " << file("s0.txt") << "\n"
                        << "screenshot " << file("f0.png") << "\n"
                        << "frame 2\n"
                        << "status " << file("s2.txt") << "\n"
                        << "screenshot " << file("f2.png") << "\n"
                        << "key space\n"
                        << "status " << file("playing.txt") << "\n"
                        << "key space\n"
                        << "status " << file("paused.txt") << "\n";
    return path;
  }

  /// Runs `isocurv view ARGS --size 480x360 --script ...` and checks what every series shows:
  /// frame 0 then frame 2 by their labels, different pictures, space playing and pausing.
  void run_view(std::vector<std::string> args, const std::string& label0, const std::string& label2) {
    args.insert(args.begin(), "view");
    for (const std::string& a : {std::string("--size"), std::string("480x360"),
                                 std::string("--script"), write_script()})
      args.push_back(a);
    const test::CliResult r = test::run_isocurv(args, 90);
    ASSERT_TRUE(r.ok()) << r.describe();
    s0 = test::read_text(file("s0.txt"));
    s2 = test::read_text(file("s2.txt"));
    EXPECT_NE(s0.find("frame 0 of 3 (" + label0), std::string::npos) << s0;
    EXPECT_NE(s2.find("frame 2 of 3 (" + label2), std::string::npos) << s2;
    EXPECT_NE(test::read_text(file("playing.txt")).find("[space] pause"), std::string::npos)
        << "space did not play";
    EXPECT_NE(test::read_text(file("paused.txt")).find("[space] play"), std::string::npos)
        << "space again did not pause";
    ASSERT_TRUE(fs::exists(file("f0.png")) && fs::exists(file("f2.png"))) << r.describe();
    EXPECT_EQ(test::png_stats(file("f0.png")).width, 480);
    EXPECT_GT(test::pixel_difference(file("f0.png"), file("f2.png")), 2000)
        << "frame 2 looks like frame 0";
  }

  /// Three tori (tube radius 0.2, 0.3, 0.4): frame_0.vtp and frame_1.vtp with their curvature
  /// arrays, frame_2.vtp without (the explorer estimates it).
  std::vector<std::string> write_torus_frames() {
    std::vector<std::string> paths;
    for (int k = 0; k < 3; ++k) {
      const test::TestSurface t = test::torus(1.f, 0.2f + 0.1f * k, 64, 32);
      paths.push_back(file("frame_" + std::to_string(k) + ".vtp"));
      io::write_mesh(paths.back(), t.mesh, k < 2 ? &t.field : nullptr);
    }
    return paths;
  }

  std::string s0, s2;  ///< the status line on frame 0 and on frame 2
};

TEST_F(VizExplorerView, VolumeSeriesPlaysItsFrames) {
  // Spheres of radius 6, 8, 10 voxels in 32^3 float volumes: |p - c| / r, cut at 1.
  for (int k = 0; k < 3; ++k) {
    std::vector<float> v(32 * 32 * 32);
    const float r = 6.f + 2.f * k;
    for (int z = 0; z < 32; ++z)
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
          v[x + 32 * (y + 32 * z)] =
              std::sqrt(float((x - 15.5) * (x - 15.5) + (y - 15.5) * (y - 15.5) + (z - 15.5) * (z - 15.5))) / r;
    std::ofstream(file("ball_" + std::to_string(k) + ".raw"), std::ios::binary)
        .write(reinterpret_cast<const char*>(v.data()), std::streamsize(v.size() * sizeof(float)));
  }
  run_view({"--time-series", file("ball_*.raw"), "--dims", "32", "32", "32", "--type", "float",
            "--iso", "1"},
           "ball_0, t = 0", "ball_2, t = 2");
  EXPECT_NE(s0.find("isovalue 1"), std::string::npos) << s0;
  EXPECT_NE(s2.find("isovalue 1"), std::string::npos) << "a new frame is cut at the same isovalue\n"
                                                      << s2;
}

TEST_F(VizExplorerView, MeshSeriesPlaysItsFiles) {
  write_torus_frames();
  run_view({"--time-series", file("frame_*.vtp")}, "frame_0, t = 0", "frame_2, t = 2");
  EXPECT_NE(s0.find("mesh of frame 0"), std::string::npos) << s0;
  EXPECT_EQ(s0.find("isovalue"), std::string::npos) << "meshes have no isovalue\n" << s0;
  EXPECT_NE(s0.find("curvature from the file"), std::string::npos) << s0;
  EXPECT_NE(s2.find("curvature estimated"), std::string::npos) << "frame 2 has no arrays\n" << s2;
  EXPECT_EQ(test::legend_difference(file("f0.png"), file("f2.png"), 0.88, 0.4), 0)
      << "every frame is coloured over the first frame's range";
}

TEST_F(VizExplorerView, MeshSeriesFromAPvdCollection) {
  const std::vector<std::string> frames = write_torus_frames();
  io::PvdCollection pvd(file("tori.pvd"));
  for (int k = 0; k < 3; ++k) pvd.add(0.25 * k, frames[k]);
  run_view({"--time-series", file("tori.pvd")}, "frame_0, t = 0", "frame_2, t = 0.5");
}

TEST(VizExplorerScript, ParsesEveryActionAndNamesTheBadLine) {
  const auto a = viz::parse_explorer_script(
      "# comment\n\nscreenshot /tmp/a b.png\nstatus s.txt\niso 0.5\nframe 3\nkey space\nkey c\n"
      "type 0.25\nresize 640 480\nwait\n");
  ASSERT_EQ(a.size(), 9u);
  using K = viz::ExplorerAction::Kind;
  EXPECT_EQ(a[0].kind, K::Screenshot);
  EXPECT_EQ(a[0].path, "/tmp/a b.png");
  EXPECT_EQ(a[1].kind, K::Status);
  EXPECT_FLOAT_EQ(a[2].isovalue, 0.5f);
  EXPECT_EQ(a[3].frame, 3);
  EXPECT_EQ(a[4].key, ' ');
  EXPECT_EQ(a[5].key, 'c');
  EXPECT_EQ(a[6].path, "0.25");
  EXPECT_EQ(a[7].width, 640);
  EXPECT_EQ(a[8].kind, K::Wait);
  for (const char* bad : {"jump 3", "frame", "frame 1.5", "iso x", "key ab", "resize 10 10",
                          "screenshot", "wait 2"}) {
    try {
      viz::parse_explorer_script(std::string("wait\n") + bad + "\n", "s.txt");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("s.txt: line 2"), std::string::npos) << e.what();
    }
  }
}

TEST_F(VizExplorerView, VolumesAndMeshesDoNotMix) {
  const std::vector<std::string> meshes = write_torus_frames();
  std::ofstream(file("vol.raw"), std::ios::binary) << std::string(8 * 8 * 8, '\0');
  const test::CliResult r =
      test::run_isocurv({"view", "--time-series", meshes[0], file("vol.raw"), "--dims", "8", "8", "8"}, 30);
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  EXPECT_NE(r.err.find("all volumes or all mesh files"), std::string::npos) << r.describe();
}
