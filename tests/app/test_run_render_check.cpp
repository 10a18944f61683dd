// isocurv run, render, check and view end to end (headless: DISPLAY unset, the CLI starts Xvfb).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli.h"
#include "io/mesh_file.h"
#include "mesh_compare.h"
#include "tests/test_paths.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

TEST(CliRun, WritesMeshPictureAndStats) {
  TempDir dir("run");
  const std::string out = dir / "out";
  const auto r = run_isocurv({"run", dataset("torus"), "-o", out, "--size", "320x240", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const std::string mesh = out + "/torus.vtp", png = out + "/torus.png", stats = out + "/stats.json";
  ASSERT_TRUE(fs::exists(mesh)) << r.describe();
  ASSERT_TRUE(fs::exists(png)) << r.describe();
  ASSERT_TRUE(fs::exists(stats)) << r.describe();
  const auto size = png_size(png);
  EXPECT_EQ(size[0], 320u);
  EXPECT_EQ(size[1], 240u);

  const json s = parse_json(read_file(stats), "stats.json");
  ASSERT_TRUE(s.is_object());
  EXPECT_EQ(parse_json(r.out, "run --json"), s) << "--json prints what stats.json holds";
  ASSERT_TRUE(s["timings_ms"].is_object()) << s.dump(2);
  for (const char* stage : {"load", "extract", "curvature", "write", "render"}) {
    ASSERT_TRUE(s["timings_ms"].contains(stage)) << stage << "\n" << s.dump(2);
    EXPECT_GE(s["timings_ms"][stage].get<double>(), 0.0);
  }
  EXPECT_GT(s["timings_ms"]["render"].get<double>(), 0.0);
  EXPECT_GT(s["vertices"].get<int>(), 1000);
  EXPECT_GT(s["triangles"].get<int>(), 2000);
  EXPECT_EQ(s["euler_characteristic"].get<int>(), 0) << "torus";
  EXPECT_EQ(s["genus"].get<int>(), 1);
  EXPECT_TRUE(s["watertight"].get<bool>());
  EXPECT_EQ(s["components"].get<int>(), 1);
  EXPECT_FALSE(s.value("device", "").empty());
  EXPECT_EQ(s.value("mesh", ""), mesh);
  EXPECT_EQ(s.value("png", ""), png);
  for (const char* q : {"H", "K"}) {
    const json& d = s["curvature"][q];
    double last = -1e30;
    for (const char* p : {"min", "p1", "p5", "p25", "p50", "p75", "p95", "p99", "max"}) {
      ASSERT_TRUE(d[p].is_number()) << q << "." << p << "\n" << s.dump(2);
      EXPECT_GE(d[p].get<double>(), last) << q << "." << p << " percentiles must be ordered";
      last = d[p].get<double>();
    }
  }
  EXPECT_LT(s["curvature"]["K"]["p1"].get<double>(), 0.0) << "the hole of the torus is saddle-shaped";
  EXPECT_GT(s["curvature"]["K"]["p99"].get<double>(), 0.0);

  const io::MeshFile m = io::read_mesh(mesh);
  EXPECT_EQ(m.mesh.positions.size(), s["vertices"].get<std::size_t>());
  ASSERT_TRUE(m.field);
  expect_complete_field(*m.field, m.mesh.positions.size(), mesh);
  // Nothing else is left in the folder (no temporary files).
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"stats.json", "torus.png", "torus.vtp"}));
}

// Output names keep every dot of the input's name but its extension's (a compressed file's two):
// "Al.100.vol" names "Al.100.vtp", not "Al.vtp"; two such inputs of a batch keep apart.
TEST(CliRun, OutputNamesDropOnlyTheExtension) {
  TempDir dir("run_dots");
  const fs::path input = dir.path() / "torus.v2.vdb", second = dir.path() / "torus.v3.vdb";
  fs::copy_file(dataset("torus"), input);
  const auto r = run_isocurv({"run", input.string(), "-o", dir / "out", "--size", "160x120", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir.path() / "out")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"stats.json", "torus.v2.png", "torus.v2.vtp"}));

  fs::copy_file(dataset("torus"), second);
  const auto b = run_isocurv({"extract", input.string(), second.string(), "-o", dir / "batch/", "--quiet"});
  ASSERT_TRUE(b.ok()) << b.describe();
  EXPECT_TRUE(fs::exists(dir.path() / "batch" / "torus.v2" / "torus.v2.vtp"));
  EXPECT_TRUE(fs::exists(dir.path() / "batch" / "torus.v3" / "torus.v3.vtp"));
}

TEST(CliRun, PlyFormatVolumeNormalsAndNestedFolder) {
  TempDir dir("run_ply");
  const std::string out = dir / "a/b";
  const auto r = run_isocurv({"run", dataset("sphere"), "-o", out, "--format", "ply", "--normals", "volume",
                              "--size", "200x100", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_TRUE(r.out.empty()) << r.out;
  ASSERT_TRUE(fs::exists(out + "/sphere.ply"));
  EXPECT_FALSE(fs::exists(out + "/sphere.vtp"));
  const json s = parse_json(read_file(out + "/stats.json"), "stats.json");
  EXPECT_EQ(s.value("normals", ""), "volume");
  EXPECT_TRUE(s["timings_ms"].contains("normals"));
  EXPECT_EQ(s["euler_characteristic"].get<int>(), 2);
  EXPECT_EQ(s["genus"].get<int>(), 0);
  EXPECT_NEAR(s["curvature"]["H"]["p50"].get<double>(), 1.25, 0.05);
  const auto size = png_size(out + "/sphere.png");
  EXPECT_EQ(size[0], 200u);
  EXPECT_EQ(size[1], 100u);
}

TEST(CliRender, ColourAoDirsAndSize) {
  TempDir dir("render");
  const std::string png = dir / "t.png";
  const auto r = run_isocurv({"render", dataset("torus"), "--color", "K", "--ao", "--dirs", "--size", "320x240", "-o",
                              png, "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "render --json");
  ASSERT_TRUE(j["timings_ms"].contains("render")) << j.dump(2);
  ASSERT_TRUE(fs::exists(png));
  const auto size = png_size(png);
  EXPECT_EQ(size[0], 320u);
  EXPECT_EQ(size[1], 240u);
  EXPECT_GT(fs::file_size(png), 5000u) << "a picture, not a blank";
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"t.png"});
}

TEST(CliRender, MeshInputWithAndWithoutCurvature) {
  TempDir dir("render_mesh");
  ASSERT_TRUE(run_isocurv({"extract", dataset("ellipsoid"), "-o", dir / "e.obj", "--quiet"}).ok());
  ASSERT_TRUE(run_isocurv({"curvature", dataset("ellipsoid"), "-o", dir / "e.vtp", "--quiet"}).ok());
  const auto plain = run_isocurv({"render", dir / "e.obj", "-o", dir / "plain.png", "--size", "160x120", "--json"});
  ASSERT_TRUE(plain.ok()) << plain.describe();
  EXPECT_TRUE(parse_json(plain.out, "render --json")["timings_ms"].contains("curvature"))
      << "a mesh without arrays gets curvature estimated";
  const auto carried = run_isocurv({"render", dir / "e.vtp", "-o", dir / "carried.png", "--size", "160x120", "--json"});
  ASSERT_TRUE(carried.ok()) << carried.describe();
  EXPECT_FALSE(parse_json(carried.out, "render --json")["timings_ms"].contains("curvature"))
      << "a mesh carrying curvature is rendered as it is";
  EXPECT_EQ(png_size(dir / "plain.png")[0], 160u);
  EXPECT_EQ(png_size(dir / "carried.png")[1], 120u);
}

TEST(CliRender, DefaultSize) {
  TempDir dir("render_default");
  const auto r = run_isocurv({"render", dataset("sphere"), "-o", dir / "s.png", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const auto size = png_size(dir / "s.png");
  EXPECT_EQ(size[0], 1024u);
  EXPECT_EQ(size[1], 768u);
}

TEST(CliRender, CameraOptions) {
  TempDir dir("render_camera");
  // The ellipsoid's axes differ, so its outline from +x and from +z differ.
  const auto side = run_isocurv({"render", dataset("ellipsoid"), "--view", "+x", "--ortho", "--size", "160x120",
                                 "-o", dir / "x.png", "--quiet"});
  ASSERT_TRUE(side.ok()) << side.describe();
  const auto top = run_isocurv({"render", dataset("ellipsoid"), "--view", "+z", "--azimuth", "10", "--elevation",
                                "-20", "--zoom", "1.5", "-o", dir / "z.png", "--size", "160x120", "--quiet"});
  ASSERT_TRUE(top.ok()) << top.describe();
  EXPECT_NE(fs::file_size(dir / "x.png"), fs::file_size(dir / "z.png"));
  const auto bad = run_isocurv({"render", dataset("ellipsoid"), "--view", "front", "-o", dir / "b.png"});
  expect_usage_error(bad, "--view");
  EXPECT_FALSE(fs::exists(dir / "b.png"));
}

TEST(CliCheck, OurOutputIsFusedAndWatertight) {
  TempDir dir("check_ours");
  ASSERT_TRUE(run_isocurv({"extract", dataset("buckyball"), "-o", dir / "b.ply", "--quiet"}).ok());
  const auto r = run_isocurv({"check", dir / "b.ply", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "check --json");
  EXPECT_EQ(j["duplicate_vertices"].get<int>(), 0);
  EXPECT_EQ(j["unreferenced_vertices"].get<int>(), 0);
  EXPECT_EQ(j["degenerate_triangles"].get<int>(), 0);
  EXPECT_EQ(j["boundary_edges"].get<int>(), 0);
  EXPECT_EQ(j["non_manifold_edges"].get<int>(), 0);
  EXPECT_TRUE(j["consistently_oriented"].get<bool>());
  EXPECT_TRUE(j["watertight"].get<bool>());
  EXPECT_TRUE(j["timings_ms"].contains("check"));
  EXPECT_EQ(j["euler_characteristic"].get<int>(), 2 * (j["components"].get<int>() - j["genus"].get<int>()));

  // Straight from the volume, text report: the torus.
  const auto t = run_isocurv({"check", dataset("torus")});
  ASSERT_TRUE(t.ok()) << t.describe();
  EXPECT_NE(t.out.find("duplicate vertices    0"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("Euler characteristic  0"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("genus                 1"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("fused and manifold, watertight"), std::string::npos) << t.out;
}

TEST(CliCheck, HandWrittenObjWithDuplicateAndBoundary) {
  TempDir dir("check_obj");
  // A unit square as two triangles whose shared corner (0,0,0) is stored twice: the diagonal is
  // then two distinct edges, so all six edges are boundary edges.
  write_file(dir / "square.obj",
             "# duplicate vertex 5 = vertex 1\n"
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 0\n"
             "f 1 2 3\nf 5 3 4\n");
  const auto r = run_isocurv({"check", dir / "square.obj", "--json"});
  ASSERT_EQ(r.exit_code, 1) << "a duplicate vertex is a problem the check reports\n" << r.describe();
  EXPECT_TRUE(r.err.empty()) << "a report, not an error: " << r.describe();
  const json j = parse_json(r.out, "check --json");
  EXPECT_EQ(j["vertices"].get<int>(), 5);
  EXPECT_EQ(j["triangles"].get<int>(), 2);
  EXPECT_EQ(j["duplicate_vertices"].get<int>(), 1);
  EXPECT_EQ(j["boundary_edges"].get<int>(), 6);
  EXPECT_EQ(j["edges"].get<int>(), 6);
  EXPECT_FALSE(j["watertight"].get<bool>());
  EXPECT_TRUE(j["genus"].is_null());
  EXPECT_NEAR(j["area"].get<double>(), 1.0, 1e-12);

  const auto text = run_isocurv({"check", dir / "square.obj"});
  ASSERT_EQ(text.exit_code, 1) << text.describe();
  EXPECT_NE(text.out.find("duplicate vertices    1"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("boundary 6"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("PROBLEMS FOUND, open"), std::string::npos) << text.out;
}

TEST(CliCheck, HandWrittenTetrahedronWithAFlippedFace) {
  TempDir dir("check_tet");
  const std::string verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  write_file(dir / "good.obj", verts + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  write_file(dir / "flipped.obj", verts + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n");
  const auto good = run_isocurv({"check", dir / "good.obj", "--json"});
  ASSERT_TRUE(good.ok()) << good.describe();
  const json g = parse_json(good.out, "check --json");
  EXPECT_TRUE(g["watertight"].get<bool>());
  EXPECT_TRUE(g["consistently_oriented"].get<bool>());
  EXPECT_EQ(g["euler_characteristic"].get<int>(), 2);
  EXPECT_EQ(g["genus"].get<int>(), 0);
  const auto bad = run_isocurv({"check", dir / "flipped.obj"});
  ASSERT_EQ(bad.exit_code, 1) << "a flipped face is a problem: " << bad.describe();
  EXPECT_NE(bad.out.find("INCONSISTENT (3 edges"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("PROBLEMS FOUND, watertight"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("genus                 n/a"), std::string::npos) << bad.out;
}

TEST(CliView, FailsCleanlyBeforeOpeningAWindow) {
  // isocurv view is interactive and has no scripted mode (app/cmd_view.cpp); the explorer itself
  // is driven by a script in tests/viz/test_explorer.cpp. Here: its input errors come before any
  // window, as one line, without hanging.
  TempDir dir("view");
  const auto missing = run_isocurv({"view", dir / "missing.vdb"}, 30);
  expect_clean_failure(missing, "missing.vdb");
  const auto iso = run_isocurv({"view", dataset("sphere"), "--iso", "42"}, 30);
  expect_clean_failure(iso, "outside the value range");
  // With no X display (DISPLAY is unset for every run here) the interactive window cannot open:
  // a clear error rather than a hang behind an invisible window.
  const auto headless = run_isocurv({"view", dataset("sphere")}, 30);
  expect_clean_failure(headless, "display");
  const auto opt = run_isocurv({"view", dataset("sphere"), "--color", "X"}, 30);
  EXPECT_NE(opt.exit_code, 0) << opt.describe();
  EXPECT_FALSE(opt.timed_out);
}

TEST(RenderOptions, ColourMapRangeShadingGlyphsAndCameraFile) {
  TempDir dir("render_options");
  const std::string vdb = dataset("torus");
  const auto a = run_isocurv({"render", vdb, "--color", "K", "--cmap", "bgr", "--range", "-2", "3", "--percentile",
                              "5", "--shading", "both", "--size", "160x120", "-o", dir / "a.png", "--quiet"});
  EXPECT_TRUE(a.ok()) << a.describe();
  const auto glyphs = run_isocurv({"render", vdb, "--dirs", "--dirs-count", "50", "--dirs-length", "0.1", "--size",
                                   "160x120", "-o", dir / "g.png", "--dirs-out", dir / "g.vtp", "--quiet"});
  ASSERT_TRUE(glyphs.ok()) << glyphs.describe();
  EXPECT_GT(fs::file_size(dir / "g.vtp"), 500u);
  // --dirs-out without --dirs, to a wrong format, and bad values: errors, nothing written
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"--dirs-out", dir / "x.vtp"}, {"--dirs", "--dirs-out", dir / "x.ply"},
        {"--range", "1", "1"}, {"--cmap", "rainbow"}, {"--shading", "phong"}, {"--percentile", "70"},
        {"--camera", dir / "missing.json"}}) {
    std::vector<std::string> args = {"render", vdb, "-o", dir / "bad.png"};
    args.insert(args.end(), bad.begin(), bad.end());
    const auto r = run_isocurv(args);
    EXPECT_NE(r.exit_code, 0) << r.describe();
    EXPECT_EQ(r.err_lines().size(), 1u) << r.describe();
    EXPECT_EQ(r.err.rfind("isocurv: ", 0), 0u) << r.describe();
    EXPECT_FALSE(fs::exists(dir / "bad.png")) << r.describe();
  }
  // a camera file (as the explorer's 'k' writes) replaces the fitted view
  write_file(dir / "cam.json",
             R"({"position": [0, 0, 8], "focal_point": [0, 0, 0], "view_up": [0, 1, 0], "ortho": false,
                 "view_angle_deg": 30, "parallel_scale": 1})");
  const auto top = run_isocurv({"render", vdb, "--camera", dir / "cam.json", "--size", "160x120", "-o",
                                dir / "top.png", "--quiet"});
  ASSERT_TRUE(top.ok()) << top.describe();
  const auto plus_z = run_isocurv({"render", vdb, "--view", "+z", "--size", "160x120", "-o", dir / "z.png", "--quiet"});
  ASSERT_TRUE(plus_z.ok()) << plus_z.describe();
  EXPECT_NE(read_file(dir / "top.png"), read_file(dir / "z.png")) << "the camera file was used";
  write_file(dir / "broken.json", R"({"position": [0, 0, 1], "focal_point": [0, 0, 1], "view_up": [0, 1, 0]})");
  const auto broken = run_isocurv({"render", vdb, "--camera", dir / "broken.json", "-o", dir / "b.png"});
  EXPECT_EQ(broken.exit_code, 1) << broken.describe();
  EXPECT_NE(broken.err.find("broken.json"), std::string::npos) << broken.describe();
}

TEST(RenderOptions, AnatomicalViewsNeedAnAnatomicalFrame) {
  TempDir dir("anatomical");
  const auto bad = run_isocurv({"render", dataset("torus"), "--view", "anterior", "-o", dir / "a.png"});
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_NE(bad.err.find("anatomical"), std::string::npos) << bad.describe();
  EXPECT_FALSE(fs::exists(dir / "a.png"));
  const std::string nifti = std::string(isocurv::test_paths::shared_datasets()) + "/mni152_t1/avg152T1_RL_nifti.nii.gz";
  if (!fs::exists(nifti)) GTEST_SKIP() << "no " << nifti;
  // NIfTI's world is RAS: anterior is the +y side, superior up, as --view +y
  const auto ant = run_isocurv({"render", nifti, "--view", "anterior", "--size", "120x90", "-o", dir / "ant.png", "--quiet"});
  const auto plus_y = run_isocurv({"render", nifti, "--view", "+y", "--size", "120x90", "-o", dir / "y.png", "--quiet"});
  ASSERT_TRUE(ant.ok() && plus_y.ok()) << ant.describe() << plus_y.describe();
  EXPECT_EQ(read_file(dir / "ant.png"), read_file(dir / "y.png"));
}

namespace {

/// A 32^3 uint8 NRRD: a ball at the centre and a small one towards +x +y +z, so the views
/// from +y and -y differ (mirror images).
std::string write_blobs_nrrd(const std::string& path, const std::string& space,
                             const std::string& directions, const std::string& more = "") {
  std::string data(32 * 32 * 32, '\0');
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const double a = std::hypot(x - 14.0, y - 14.0, z - 14.0),
                     b = std::hypot(x - 22.0, y - 22.0, z - 20.0);
        const bool in = a < 8 || b < 4;
        data[static_cast<std::size_t>(x + 32 * (y + 32 * z))] = static_cast<char>(in ? 200 : 10);
      }
  write_file(
      path, "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 32 32 32\nencoding: raw\nspace: " + space +
                "\nspace directions: " + directions + "\nspace origin: (0,0,0)\n" + more + "\n" + data);
  return path;
}

}  // namespace

TEST(RenderOptions, NrrdSpaceGivesTheAnatomicalViews) {
  TempDir dir("nrrd_views");
  auto render = [&](const std::string& in, const std::string& view, const std::string& png) {
    const auto r = run_isocurv({"render", in, "--iso", "100", "--view", view, "--size", "120x90",
                                "-o", dir / png, "--quiet"});
    EXPECT_TRUE(r.ok()) << r.describe();
    return read_file(dir / png);
  };
  // LPS with flipped x and y directions: anterior is world -y
  const std::string lps =
      write_blobs_nrrd(dir / "lps.nrrd", "left-posterior-superior", "(-1,0,0) (0,-1,0) (0,0,1)");
  const std::string ant = render(lps, "anterior", "lps_ant.png");
  EXPECT_EQ(ant, render(lps, "-y", "lps_my.png"));
  EXPECT_NE(ant, render(lps, "+y", "lps_py.png")) << "anterior must not be +y in LPS";
  // RAS: anterior is world +y
  const std::string ras =
      write_blobs_nrrd(dir / "ras.nrrd", "right-anterior-superior", "(1,0,0) (0,1,0) (0,0,1)");
  EXPECT_EQ(render(ras, "anterior", "ras_ant.png"), render(ras, "+y", "ras_py.png"));
  const auto info = run_isocurv({"info", lps, "--json"});
  ASSERT_TRUE(info.ok()) << info.describe();
  EXPECT_EQ(parse_json(info.out, "info").value("world_space", ""), "LPS");
}

TEST(RenderOptions, AnatomicalVolumesDefaultToTheFaceWithSuperiorUp) {
  TempDir dir("anatomical_default");
  auto render = [&](const std::string& in, std::vector<std::string> extra, const std::string& png) {
    std::vector<std::string> args = {"render", in, "--iso", "100", "--size", "120x90",
                                     "-o", dir / png, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args);
    EXPECT_TRUE(r.ok()) << r.describe();
    return read_file(dir / png);
  };
  // RAS: the face is +y; LPS: -y. The default is iso from the front (turned 35, raised 30).
  const std::string ras =
      write_blobs_nrrd(dir / "ras.nrrd", "right-anterior-superior", "(1,0,0) (0,1,0) (0,0,1)");
  const std::string lps =
      write_blobs_nrrd(dir / "lps.nrrd", "left-posterior-superior", "(1,0,0) (0,1,0) (0,0,1)");
  const std::string ras_default = render(ras, {}, "ras.png");
  EXPECT_EQ(ras_default, render(ras, {"--view", "+y", "--azimuth", "35", "--elevation", "30"}, "ras_y.png"));
  EXPECT_NE(ras_default, render(ras, {"--view", "iso"}, "ras_iso.png")) << "--view iso is the plain iso";
  EXPECT_EQ(render(lps, {}, "lps.png"),
            render(lps, {"--view", "-y", "--azimuth", "35", "--elevation", "30"}, "lps_y.png"));
  // --view-up by anatomical name and by vector; a raw volume has no anatomical names.
  EXPECT_EQ(render(ras, {"--view", "+x", "--view-up", "inferior"}, "ras_inf.png"),
            render(ras, {"--view", "+x", "--view-up", "-z"}, "ras_mz.png"));
  EXPECT_NE(render(ras, {"--view", "+x", "--view-up", "-z"}, "a.png"),
            render(ras, {"--view", "+x"}, "b.png"));
  const auto along = run_isocurv({"render", ras, "--iso", "100", "--view", "+x", "--view-up",
                                  "1,0,0", "-o", dir / "along.png"});
  expect_clean_failure(along, "--view-up");
  const auto raw = run_isocurv({"render", dataset("torus"), "--view-up", "superior", "-o",
                                dir / "raw.png"});
  expect_clean_failure(raw, "anatomical");
  EXPECT_FALSE(fs::exists(dir / "along.png"));
  EXPECT_FALSE(fs::exists(dir / "raw.png"));
}

TEST(RenderOptions, ASavedMeshKeepsItsIsovalueEstimatorUnitAndFrame) {
  TempDir dir("context_round_trip");
  const std::string ras = write_blobs_nrrd(dir / "ras.nrrd", "right-anterior-superior",
                                           "(1,0,0) (0,1,0) (0,0,1)",
                                           "space units: \"mm\" \"mm\" \"mm\"\n");
  const auto info = run_isocurv({"info", ras, "--json"});
  ASSERT_TRUE(info.ok()) << info.describe();
  EXPECT_EQ(parse_json(info.out, "info").value("length_unit", ""), "mm");
  const std::string mesh = dir / "ras.vtp";
  const auto c = run_isocurv({"curvature", ras, "--iso", "100", "-o", mesh, "--quiet"});
  ASSERT_TRUE(c.ok()) << c.describe();
  const io::MeshFile m = io::read_mesh(mesh);
  auto meta = [&](const io::MeshFile& f, const std::string& key) {
    for (const auto& [k, v] : f.metadata)
      if (k == key) return v;
    return std::string();
  };
  EXPECT_EQ(meta(m, "isovalue"), "100");
  EXPECT_EQ(meta(m, "length_unit"), "mm");
  EXPECT_EQ(meta(m, "world_space"), "RAS");
  EXPECT_EQ(meta(m, "source"), "ras.nrrd");
  EXPECT_EQ(meta(m, "estimator"), "volume");
  const auto r = run_isocurv({"render", mesh, "--size", "200x150", "-o", dir / "m.png", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "render --json");
  const std::string title = j.value("title", "");
  EXPECT_NE(title.find("iso 100"), std::string::npos) << title;
  EXPECT_NE(title.find("from the file: volume, scale"), std::string::npos) << title;
  EXPECT_NE(j.value("legend_title", "").find("1/mm"), std::string::npos) << j.dump();
  // The frame came with the mesh: anatomical views work on it, and match the volume's.
  const auto a = run_isocurv({"render", mesh, "--view", "anterior", "--size", "120x90", "-o",
                              dir / "ma.png", "--quiet"});
  ASSERT_TRUE(a.ok()) << a.describe();
  // --unit given to run survives into the mesh and back.
  const auto run = run_isocurv({"run", dataset("torus"), "--unit", "um", "-o", dir / "out", "--quiet"});
  ASSERT_TRUE(run.ok()) << run.describe();
  const auto back = run_isocurv({"render", dir / "out/torus.vtp", "--size", "200x150", "-o",
                                 dir / "t.png", "--json"});
  ASSERT_TRUE(back.ok()) << back.describe();
  EXPECT_NE(parse_json(back.out, "render").value("legend_title", "").find("1/um"), std::string::npos)
      << back.out;
  // A mesh from elsewhere (no field data) still renders, with no isovalue in its title.
  const auto obj = run_isocurv({"extract", dataset("torus"), "-o", dir / "t.obj", "--quiet"});
  ASSERT_TRUE(obj.ok()) << obj.describe();
  const auto plain = run_isocurv({"render", dir / "t.obj", "--size", "200x150", "-o", dir / "o.png", "--json"});
  ASSERT_TRUE(plain.ok()) << plain.describe();
  EXPECT_EQ(parse_json(plain.out, "render").value("title", "").find("iso "), std::string::npos);
}

TEST(RenderColor, AnyPointArrayWithItsRangeAndUnknownNamesListed) {
  TempDir dir("color_arrays");
  const std::string base = dir / "torus.vtp";
  const auto c = run_isocurv({"curvature", dataset("torus"), "-o", base, "--quiet"});
  ASSERT_TRUE(c.ok()) << c.describe();
  io::MeshFile m = io::read_mesh(base);
  ASSERT_TRUE(m.field);
  const std::size_t n = m.mesh.positions.size();
  std::vector<float> lbe(n), h2(n);
  for (std::size_t i = 0; i < n; ++i) {
    lbe[i] = 3.f + float(i % 1000) / 1000.f;  // [3, 4)
    h2[i] = float(i % 100) / 100.f - 0.4f;    // [-0.4, 0.59]: both signs, more positive
  }
  m.field->extra.push_back({"LBE_r0.3", lbe});
  m.field->extra.push_back({"H_s2", h2});
  const std::string mesh = dir / "extras.vtp";
  io::write_mesh(mesh, m.mesh, &*m.field);

  auto range_of = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", mesh,          "--size", "200x150",
                                     "-o",     dir / "x.png", "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args);
    EXPECT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "render --json");
    return std::pair<double, double>{j["color"]["range"][0].get<double>(),
                                     j["color"]["range"][1].get<double>()};
  };
  std::vector<float> sorted = lbe;
  std::sort(sorted.begin(), sorted.end());
  const auto [lo, hi] = range_of({"--color", "LBE_r0.3"});
  EXPECT_NEAR(lo, sorted[static_cast<std::size_t>(0.02 * double(n - 1) + 0.5)], 2e-3);
  EXPECT_NEAR(hi, sorted[static_cast<std::size_t>(0.98 * double(n - 1) + 0.5)], 2e-3);
  const auto [hlo, hhi] = range_of({"--color", "H_s2"});
  EXPECT_DOUBLE_EQ(hlo, -hhi) << "a suffixed H is symmetric about zero";
  const auto [flo, fhi] = range_of({"--color", "LBE_r0.3", "--range", "3.25", "3.5"});
  EXPECT_EQ(flo, 3.25);
  EXPECT_EQ(fhi, 3.5);
  // --flip re-estimates the curvature: the file's extra arrays must survive it
  const auto flipped = run_isocurv({"render", mesh, "--flip", "--color", "LBE_r0.3", "--size",
                                    "200x150", "-o", dir / "f.png", "--quiet"});
  EXPECT_TRUE(flipped.ok()) << flipped.describe();
  const auto bad = run_isocurv({"render", mesh, "--color", "H_ii", "-o", dir / "bad.png"});
  EXPECT_EQ(bad.exit_code, 1) << bad.describe();
  EXPECT_EQ(bad.err_lines().size(), 1u) << bad.describe();
  EXPECT_NE(bad.err.find("H_ii"), std::string::npos) << bad.describe();
  EXPECT_NE(bad.err.find("LBE_r0.3"), std::string::npos)
      << "the error lists the mesh's arrays: " << bad.describe();
  EXPECT_FALSE(fs::exists(dir / "bad.png"));
}
