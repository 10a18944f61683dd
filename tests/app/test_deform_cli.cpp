// isocurv deform end to end: frames, the .pvd collection, timings.json, and one-line errors for
// bad skins and options (nothing written for them).
#include <gtest/gtest.h>

#include <string>

#include "cli.h"
#include "io/mesh_file.h"
#include "io/pvd_collection.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

// A skin for `vertices` vertices, every one on bone 0, or `weight` where given.
std::string skin_json(std::size_t vertices, const std::string& pair = "[0, 1.0]") {
  std::string w = "[";
  for (std::size_t i = 0; i < vertices; ++i) w += (i ? ",[" : "[") + pair + "]";
  return R"({"bones": [{"name": "root", "pivot": [0, 0, 0]}], "weights": )" + w + R"(],
             "keyframes": [{"time": 0, "pose": [{}]},
                           {"time": 1, "pose": [{"rotation": [0.9238795, 0, 0, 0.3826834],
                                                 "translation": [0.1, 0, 0]}]}]})";
}

TEST(CliDeform, AffineFramesCollectionAndTimings) {
  TempDir dir("deform");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "ball.vtp", "--quiet"}).ok());
  const auto r = run_isocurv({"deform", dir / "ball.vtp", "--deformer", "affine", "--frames", "4",
                              "-o", dir / "anim", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "deform --json");
  EXPECT_EQ(j["frames"], 4);
  EXPECT_GT(j["frames_per_second"].get<double>(), 0);
  const std::vector<io::PvdFrame> frames = io::read_pvd(dir / "anim/ball.pvd");
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_DOUBLE_EQ(frames[1].time, 0.25);
  const io::MeshFile rest = io::read_mesh(dir / "ball.vtp");
  const io::MeshFile f1 = io::read_mesh(frames[1].file);
  ASSERT_EQ(f1.mesh.vertex_count(), rest.mesh.vertex_count());
  ASSERT_TRUE(f1.field && !f1.field->H.empty() && !f1.field->dir1.empty());
  // Frame 1: x scaled by a = 1 + 0.5 sin(pi / 2) = 1.5.
  EXPECT_NEAR(f1.mesh.positions[7][0], 1.5f * rest.mesh.positions[7][0], 1e-5);
  const json t = parse_json(read_file(dir / "anim/timings.json"), "timings.json");
  ASSERT_EQ(t["per_frame"].size(), 4u);
  EXPECT_TRUE(t["per_frame"][3]["timings_ms"].contains("curvature"));
}

TEST(CliDeform, SkinAndNoise) {
  TempDir dir("deform_skin");
  ASSERT_TRUE(run_isocurv({"extract", dataset("torus"), "-o", dir / "t.ply", "--quiet"}).ok());
  const std::size_t nv = io::read_mesh(dir / "t.ply").mesh.vertex_count();
  write_file(dir / "rig.json", skin_json(nv));
  const auto r = run_isocurv({"deform", dir / "t.ply", "--deformer", "skin", "--skin",
                              dir / "rig.json", "--frames", "3", "-o", dir / "skin", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const std::vector<io::PvdFrame> frames = io::read_pvd(dir / "skin/t.pvd");
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_DOUBLE_EQ(frames[2].time, 1.0);
  // The last frame is the rigid motion: same curvature as the rest pose up to float noise.
  const io::MeshFile f0 = io::read_mesh(frames[0].file), f2 = io::read_mesh(frames[2].file);
  double worst = 0;
  for (std::size_t i = 0; i < nv; ++i)
    worst = std::max(worst, double(std::abs(f0.field->H[i] - f2.field->H[i])));
  EXPECT_LT(worst, 1e-2);
  EXPECT_GT(std::abs(f2.mesh.positions[0][0] - f0.mesh.positions[0][0]), 1e-3);  // it moved

  const auto n = run_isocurv({"deform", dir / "t.ply", "--deformer", "noise", "--frames", "2",
                              "--estimator", "batagelo", "-o", dir / "noise", "--quiet"});
  ASSERT_TRUE(n.ok()) << n.describe();
  EXPECT_EQ(io::read_pvd(dir / "noise/t.pvd").size(), 2u);
}

TEST(CliDeform, BadInputIsOneLineAndWritesNothing) {
  TempDir dir("deform_bad");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "s.vtp", "--quiet"}).ok());
  const std::size_t nv = io::read_mesh(dir / "s.vtp").mesh.vertex_count();
  auto deform_skin = [&](const std::string& text) {
    write_file(dir / "rig.json", text);
    return run_isocurv({"deform", dir / "s.vtp", "--deformer", "skin", "--skin", dir / "rig.json",
                        "-o", dir / "out"});
  };
  expect_clean_failure(deform_skin("{\"bones\": [{}], "), "not valid JSON");
  expect_clean_failure(deform_skin(skin_json(nv, "[3, 1.0]")), "refers to bone 3");
  expect_clean_failure(deform_skin(skin_json(nv, "[0, 0.5]")), "weights sum to 0.5");
  expect_clean_failure(deform_skin(skin_json(nv + 1)), "but the mesh has " + std::to_string(nv));
  expect_clean_failure(
      run_isocurv({"deform", dir / "s.vtp", "--deformer", "skin", "-o", dir / "out"}), "--skin");
  expect_clean_failure(
      run_isocurv({"deform", dir / "s.vtp", "--deformer", "twist", "-o", dir / "out"}),
      "--deformer");
  expect_clean_failure(
      run_isocurv({"deform", dataset("sphere"), "--deformer", "affine", "-o", dir / "out"}),
      "mesh file");
  expect_clean_failure(run_isocurv({"deform", dir / "s.vtp", "--deformer", "affine", "--estimator",
                                    "meyer", "-o", dir / "out"}),
                       "--estimator");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace

// A rig with one keyframe gives every frame the same time: it once wrote its frames and a .pvd,
// then failed naming the .pvd. Rigs are checked before anything is written, the error names the
// rig (issue 41).
TEST(CliDeform, OneKeyframeRigRefusedBeforeAnythingIsWritten) {
  TempDir dir("deform_one_key");
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "s.vtp", "--quiet"}).ok());
  const std::size_t nv = io::read_mesh(dir / "s.vtp").mesh.vertex_count();
  std::string w = "[";
  for (std::size_t i = 0; i < nv; ++i) w += std::string(i ? "," : "") + "[[0, 1.0]]";
  write_file(dir / "one_key.json", R"({"bones": [{"name": "root"}], "weights": )" + w +
                                       R"(], "keyframes": [{"time": 0.5, "pose": [{}]}]})");
  const auto r = run_isocurv({"deform", dir / "s.vtp", "--deformer", "skin", "--skin",
                              dir / "one_key.json", "--frames", "3", "-o", dir / "out"});
  expect_clean_failure(r, "one_key.json: the rig has one keyframe");
  EXPECT_FALSE(fs::exists(dir / "out")) << "nothing may be written for a bad rig";
}
