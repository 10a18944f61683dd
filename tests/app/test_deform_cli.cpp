// isocurv deform end to end: frames, the .pvd collection, timings.json, and one-line errors for
// bad skins and options (nothing written for them); the sample rig the build ships
// (build/datasets/finger.vtp and finger_rig.json), and every estimator either run on the prepared
// path or refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "cli.h"
#include "curvature/estimator.h"
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

namespace {

// The sample the build generates (datasets/make_sample_rig_main.cpp): a capsule along z, radius
// 0.25, body z in [-1, 1]; the "tip" bone bends 90 degrees about x at t = 1 and back at t = 2,
// the weights blend from all "base" at z <= -0.5 to all "tip" at z >= 0.5.
std::string finger_mesh() { return build_dir() + "/datasets/finger.vtp"; }
std::string finger_rig() { return build_dir() + "/datasets/finger_rig.json"; }

double max_abs_diff(const std::vector<float>& a, const std::vector<float>& b,
                    const std::vector<std::size_t>& where) {
  double worst = 0;
  for (std::size_t i : where) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

}  // namespace

// The docs' sample (docs/time-series.md, "Deforming meshes"): the fixed end keeps its curvature
// exactly, the rigidly moved tip keeps it up to float noise, the blend zone changes it, and the
// last keyframe is the rest pose again.
TEST(CliDeform, SampleFingerRigBendsWhereTheBonesBlend) {
  TempDir dir("deform_finger");
  const auto r = run_isocurv({"deform", finger_mesh(), "--deformer", "skin", "--skin", finger_rig(),
                              "--frames", "5", "-o", dir / "bend", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "deform --json");
  EXPECT_EQ(j["frames"], 5);
  const io::MeshFile rest = io::read_mesh(finger_mesh());
  const std::size_t nv = rest.mesh.vertex_count();
  EXPECT_EQ(nv, 3410u);
  EXPECT_EQ(j["vertices"], nv);
  const std::vector<io::PvdFrame> frames = io::read_pvd(dir / "bend/finger.pvd");
  ASSERT_EQ(frames.size(), 5u);
  std::vector<io::MeshFile> f;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_DOUBLE_EQ(frames[i].time, 0.5 * double(i));  // the keyframe span [0, 2]
    f.push_back(io::read_mesh(frames[i].file));
    ASSERT_EQ(f[i].mesh.vertex_count(), nv) << "frame " << i;
    ASSERT_TRUE(f[i].mesh.triangles == rest.mesh.triangles) << "frame " << i;
    ASSERT_TRUE(f[i].field && f[i].field->H.size() == nv) << "frame " << i;
  }
  std::vector<std::size_t> fixed, blend, tip, body;
  for (std::size_t i = 0; i < nv; ++i) {
    const float z = rest.mesh.positions[i][2];
    if (z < -0.6f) fixed.push_back(i);
    if (std::abs(z) < 0.5f) blend.push_back(i);
    if (z > 0.6f) tip.push_back(i);
    if (std::abs(z) < 0.9f) body.push_back(i);
  }
  // Wound outward: the cylinder's H is +1/(2 r) = 2 at rest.
  std::vector<float> h;
  for (std::size_t i : body) h.push_back(f[0].field->H[i]);
  std::nth_element(h.begin(), h.begin() + long(h.size() / 2), h.end());
  EXPECT_NEAR(h[h.size() / 2], 2.0, 0.02);
  // The tip's pole, (0, 0, 1.25) at rest, is at (0, -1.25, 0) at the full bend (frame 2, t = 1).
  const Vec3f pole = f[2].mesh.positions[nv - 1];
  EXPECT_NEAR(pole[0], 0, 1e-5);
  EXPECT_NEAR(pole[1], -1.25, 1e-5);
  EXPECT_NEAR(pole[2], 0, 1e-5);
  const std::vector<float>& h0 = f[0].field->H;
  for (int i : {1, 2, 3}) {
    SCOPED_TRACE("frame " + std::to_string(i));
    for (std::size_t v : fixed)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(f[i].mesh.positions[v][c], rest.mesh.positions[v][c], 1e-6) << v;
    EXPECT_LT(max_abs_diff(f[i].field->H, h0, fixed), 1e-4) << "the fixed end's curvature changed";
    EXPECT_LT(max_abs_diff(f[i].field->H, h0, tip), 0.02) << "a rigid motion changed curvature";
    EXPECT_GT(max_abs_diff(f[i].field->H, h0, blend), i == 2 ? 5.0 : 0.5)
        << "the blend zone did not bend";
  }
  // t = 2 is the rest pose again.
  for (std::size_t v = 0; v < nv; ++v)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(f[4].mesh.positions[v][c], rest.mesh.positions[v][c], 1e-6) << v;
  std::vector<std::size_t> all(nv);
  for (std::size_t v = 0; v < nv; ++v) all[v] = v;
  EXPECT_LT(max_abs_diff(f[4].field->H, h0, all), 1e-3);
}

// Every estimator either runs through deform's prepared path, each frame matching a cold
// `isocurv curvature` of that frame's mesh, or is refused in one line that names it and the
// estimators that have the path, before anything is written.
TEST(CliDeform, EveryEstimatorRunsPreparedOrIsRefusedByName) {
  TempDir dir("deform_estimators");
  std::set<std::string> ran;
  for (const std::string& name : curvature::estimator_names()) {
    SCOPED_TRACE(name);
    const std::string out = dir / ("prepared_" + name);
    const auto r = run_isocurv({"deform", finger_mesh(), "--deformer", "skin", "--skin",
                                finger_rig(), "--frames", "3", "--estimator", name, "-o", out,
                                "--quiet"});
    if (!r.ok()) {
      expect_clean_failure(r, "--estimator " + name + ": deform runs only rusinkiewicz, "
                              "batagelo, prantl3 and prantl2; " + name);
      EXPECT_FALSE(fs::exists(out)) << "nothing may be written for a refused estimator";
      continue;
    }
    ran.insert(name);
    const std::string bent = out + "/finger_0001.vtp";  // t = 1, the full bend
    const std::string cold = dir / ("cold_" + name + ".vtp");
    const auto c = run_isocurv({"curvature", bent, "--estimator", name, "-o", cold, "--quiet"});
    ASSERT_TRUE(c.ok()) << c.describe();
    const io::MeshFile p = io::read_mesh(bent), q = io::read_mesh(cold);
    ASSERT_TRUE(p.field && q.field);
    ASSERT_EQ(p.mesh.vertex_count(), q.mesh.vertex_count());
    const auto& a = *p.field;
    const auto& b = *q.field;
    for (const auto& [what, x, y] :
         {std::tuple{"H", &a.H, &b.H}, {"K", &a.K, &b.K}, {"k1", &a.k1, &b.k1},
          {"k2", &a.k2, &b.k2}}) {
      ASSERT_EQ(x->size(), y->size()) << what;
      ASSERT_FALSE(x->empty()) << what;
      for (std::size_t i = 0; i < x->size(); ++i)
        ASSERT_NEAR((*x)[i], (*y)[i], 1e-5 * (1 + std::abs((*y)[i]))) << what << " vertex " << i;
    }
  }
  for (const char* name : {"rusinkiewicz", "batagelo", "prantl3", "prantl2"})
    EXPECT_EQ(ran.count(name), 1u) << name << " has a prepared path";
  EXPECT_EQ(ran.count("volume"), 0u) << "volume needs a volume";
}
