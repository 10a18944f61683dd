// --time-series end to end through the executable: frames in natural order, the .pvd read back
// (by io::read_pvd and by VTK's own XML parser), the pulsing sphere's per-frame curvature, the
// grids of a multi-grid .vdb as frames, a bad frame, flipbooks bit-identical to the single-file
// command, features and lines over a series, and peak memory that does not grow with frames.
#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <cmath>
#include <set>

#include "datasets/animated.h"
#include "datasets/sample.h"
#include "datasets/write_vdb.h"
#include "io/mesh_file.h"
#include "io/pvd_collection.h"
#include "tests/app/cli.h"
#include "tests/viz/png_stats.h"

namespace isocurv::test {
namespace {

constexpr int kFrames = 16;  // ISOCURV_DATASET_FRAMES

std::string frame_of(const std::string& name, int i) {
  return build_dir() + "/datasets/" + name + "/" + name + "_" + std::to_string(i) + ".vdb";
}

/// The DataSet entries of a .pvd as VTK's XML parser sees them: (timestep, file).
std::vector<std::pair<double, std::string>> vtk_pvd_entries(const std::string& path) {
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(path.c_str());
  std::vector<std::pair<double, std::string>> out;
  if (!parser->Parse()) {
    ADD_FAILURE() << "VTK cannot parse " << path;
    return out;
  }
  vtkXMLDataElement* root = parser->GetRootElement();
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* c = root->FindNestedElementWithName("Collection");
  if (!c) {
    ADD_FAILURE() << "no Collection in " << path;
    return out;
  }
  for (int i = 0; i < c->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* d = c->GetNestedElement(i);
    double t = std::nan("");
    EXPECT_TRUE(d->GetScalarAttribute("timestep", t));
    out.emplace_back(t, d->GetAttribute("file") ? d->GetAttribute("file") : "");
  }
  return out;
}

/// RMS of (H - 1/r) r over the vertices: the relative mean-curvature error on a sphere of radius r.
double rms_relative_H_error(const io::MeshFile& f, double r) {
  double sum = 0;
  for (float h : f.field->H) sum += (h * r - 1) * (h * r - 1);
  return std::sqrt(sum / f.field->H.size());
}

TEST(SeriesCli, PulsingSphereFramesPvdAndCurvature) {
  TempDir dir("pulse");
  // Frames given in the shell's (lexicographic) order: _10 before _2. The series is natural.
  std::vector<std::string> args = {"curvature", "--time-series"};
  for (int i : {0, 1, 10, 11, 12, 13, 14, 15, 2, 3, 4, 5, 6, 7, 8, 9})
    args.push_back(frame_of("pulsing_sphere", i));
  for (const char* a : {"-o", "", "--time-step", "0.0625", "--json"}) args.push_back(a);
  args[args.size() - 4] = dir / "out";
  const auto r = run_isocurv(args, 300);
  ASSERT_TRUE(r.ok()) << r.describe();
  const nlohmann::json j = parse_json(r.out, "series --json");
  EXPECT_EQ(j["frames"], kFrames);
  EXPECT_EQ(j["written"], kFrames);
  EXPECT_EQ(j, parse_json(read_file(dir / "out/series.json"), "series.json"));

  const auto pvd = io::read_pvd(dir / "out/series.pvd");
  const auto vtk = vtk_pvd_entries(dir / "out/series.pvd");
  ASSERT_EQ(pvd.size(), std::size_t(kFrames));
  ASSERT_EQ(vtk.size(), std::size_t(kFrames));
  // The static sphere's bound (tests/app, CliCurvature.MeshAndVolumeNormalsOnTheSphere): the
  // median H within 0.05 of 1/R at R = 0.8, 4% relative. Every frame, pulsing from R = 0.4 to
  // 0.8, keeps its RMS relative error under the same 4%, and its median H under it too.
  double worst = 0;
  for (int i = 0; i < kFrames; ++i) {
    const nlohmann::json& e = j["entries"][i];
    EXPECT_EQ(e["status"], "ok");
    EXPECT_EQ(e["input"], frame_of("pulsing_sphere", i)) << "natural order";
    EXPECT_DOUBLE_EQ(e["time"].get<double>(), i * 0.0625);
    EXPECT_DOUBLE_EQ(pvd[i].time, i * 0.0625);
    EXPECT_DOUBLE_EQ(vtk[i].first, i * 0.0625);
    EXPECT_EQ(fs::path(vtk[i].second).filename().string(),
              "pulsing_sphere_" + std::to_string(i) + ".vtp");
    for (const char* k : {"load", "extract", "curvature", "write"})
      EXPECT_TRUE(e["timings_ms"].contains(k)) << k;
    EXPECT_TRUE(e["curvature"]["H"]["p50"].is_number());
    EXPECT_GT(e["peak_rss_kb"].get<long>(), 0);
    const double radius = datasets::pulsing_sphere_radius(i / double(kFrames));
    const io::MeshFile f = io::read_mesh(pvd[i].file);
    ASSERT_TRUE(f.field.has_value());
    const double err = rms_relative_H_error(f, radius);
    worst = std::max(worst, err);
    EXPECT_LT(err, 0.04) << "frame " << i << " R = " << radius;
    EXPECT_NEAR(e["curvature"]["H"]["p50"].get<double>() * radius, 1.0, 0.04) << "frame " << i;
    EXPECT_EQ(e["vertices"].get<std::size_t>(), f.mesh.positions.size());
  }
  std::printf("pulsing sphere, %d frames of 64^3: worst per-frame RMS relative H error %.4f\n",
              kFrames, worst);
}

TEST(SeriesCli, MultiGridVdbGridsAreFramesInNaturalOrder) {
  TempDir dir("grids");
  const auto r =
      run_isocurv({"extract", "--time-series", build_dir() + "/datasets/pulsing_sphere_grids.vdb",
                   "-o", dir / "out", "--json"},
                  300);
  ASSERT_TRUE(r.ok()) << r.describe();
  const nlohmann::json j = parse_json(r.out, "series --json");
  ASSERT_EQ(j["entries"].size(), std::size_t(kFrames));
  const auto pvd = io::read_pvd(dir / "out/series.pvd");
  ASSERT_EQ(pvd.size(), std::size_t(kFrames));
  for (int i = 0; i < kFrames; ++i) {
    EXPECT_EQ(j["entries"][i]["grid"], "frame_" + std::to_string(i));  // frame_10 after frame_9
    EXPECT_DOUBLE_EQ(pvd[i].time, i);
    if (i % 5 != 0) continue;  // a few against the file series: the same mesh
    const auto one = run_isocurv({"extract", frame_of("pulsing_sphere", i), "-o", dir / "one.vtp"});
    ASSERT_TRUE(one.ok()) << one.describe();
    const io::MeshFile a = io::read_mesh(pvd[i].file), b = io::read_mesh(dir / "one.vtp");
    EXPECT_EQ(a.mesh.positions, b.mesh.positions) << "frame " << i;
    EXPECT_EQ(a.mesh.triangles, b.mesh.triangles) << "frame " << i;
  }
}

TEST(SeriesCli, BadFrameStopsWithOneLineAndKeepsTheFramesBefore) {
  TempDir dir("bad");
  fs::create_directories(dir / "in");
  for (int i = 0; i < 4; ++i)
    fs::copy_file(frame_of("metaballs", i), dir / ("in/m_" + std::to_string(i) + ".vdb"));
  const std::string good = read_file(dir / "in/m_2.vdb");
  write_file(dir / "in/m_2.vdb", good.substr(0, good.size() / 2));  // cut in half
  const auto r =
      run_isocurv({"curvature", "--time-series", dir / "in/m_*.vdb", "-o", dir / "out"}, 300);
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  expect_one_error_line(r, "m_2.vdb");
  EXPECT_NE(r.err.find("frame 2 of 4"), std::string::npos) << r.describe();
  EXPECT_TRUE(fs::exists(dir / "out/m_0.vtp"));
  EXPECT_TRUE(fs::exists(dir / "out/m_1.vtp"));
  EXPECT_FALSE(fs::exists(dir / "out/m_2.vtp"));
  EXPECT_FALSE(fs::exists(dir / "out/m_3.vtp"));
  const auto pvd = io::read_pvd(dir / "out/series.pvd");
  ASSERT_EQ(pvd.size(), 2u);
  EXPECT_EQ(vtk_pvd_entries(dir / "out/series.pvd").size(), 2u);
  for (const auto& f : pvd) EXPECT_GT(io::read_mesh(f.file).mesh.positions.size(), 100u) << f.file;
  const nlohmann::json j = parse_json(read_file(dir / "out/series.json"), "series.json");
  EXPECT_EQ(j["status"], "failed");
  ASSERT_EQ(j["entries"].size(), 3u);
  EXPECT_EQ(j["entries"][2]["status"], "failed");
}

TEST(SeriesCli, FlipbookFramesAreBitIdenticalToTheSingleFileCommand) {
  TempDir dir("flip");
  fs::create_directories(dir / "meshes");
  // A flipbook: a mesh per frame, each with its own connectivity (metaballs merge and split).
  for (int i : {0, 3, 6, 9, 12}) {
    const auto e = run_isocurv({"extract", frame_of("metaballs", i), "-o",
                                dir / ("meshes/blob_" + std::to_string(i) + ".ply")});
    ASSERT_TRUE(e.ok()) << e.describe();
  }
  const auto r = run_isocurv(
      {"curvature", "--time-series", dir / "meshes/*.ply", "-o", dir / "out", "--quiet"}, 300);
  ASSERT_TRUE(r.ok()) << r.describe();
  const auto pvd = io::read_pvd(dir / "out/series.pvd");
  ASSERT_EQ(pvd.size(), 5u);
  std::set<std::size_t> sizes;
  int k = 0;
  for (int i : {0, 3, 6, 9, 12}) {  // natural order: blob_12 last
    const std::string stem = "blob_" + std::to_string(i);
    EXPECT_EQ(fs::path(pvd[k++].file).filename().string(), stem + ".vtp");
    const auto one = run_isocurv(
        {"curvature", dir / ("meshes/" + stem + ".ply"), "-o", dir / "one.vtp", "--quiet"});
    ASSERT_TRUE(one.ok()) << one.describe();
    const std::string a = read_file(dir / ("out/" + stem + ".vtp")), b = read_file(dir / "one.vtp");
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << stem << ": the series frame differs from the single-file output";
    sizes.insert(io::read_mesh(dir / "one.vtp").mesh.positions.size());
  }
  EXPECT_GT(sizes.size(), 1u) << "the frames should have different connectivity";
}

TEST(SeriesCli, RunFeaturesAndLinesOverASeries) {
  TempDir dir("cmds");
  const std::vector<std::string> frames = {frame_of("gyroid_phase", 0),
                                           frame_of("gyroid_phase", 5)};
  {
    auto args = std::vector<std::string>{"lines", "--time-series"};
    args.insert(args.end(), frames.begin(), frames.end());
    args.insert(args.end(), {"-o", dir / "lines"});
    const auto r = run_isocurv(args, 300);
    ASSERT_TRUE(r.ok()) << r.describe();
    EXPECT_EQ(io::read_pvd(dir / "lines/series.pvd").size(), 2u);
    EXPECT_TRUE(fs::exists(dir / "lines/gyroid_phase_5.vtp"));
  }
  {
    auto args = std::vector<std::string>{"run", "--time-series"};
    args.insert(args.end(), frames.begin(), frames.end());
    args.insert(args.end(), {"-o", dir / "run", "--size", "160x120"});
    const auto r = run_isocurv(args, 300);
    ASSERT_TRUE(r.ok()) << r.describe();
    const auto pvd = io::read_pvd(dir / "run/series.pvd");
    ASSERT_EQ(pvd.size(), 2u);
    EXPECT_EQ(fs::path(pvd[1].file).string(), dir / "run/gyroid_phase_5/gyroid_phase_5.vtp");
    EXPECT_TRUE(fs::exists(dir / "run/gyroid_phase_5/gyroid_phase_5.png"));
    EXPECT_TRUE(fs::exists(dir / "run/gyroid_phase_5/stats.json"));
  }
  {
    // Features on two small frames (the reference is ~0.1 ms per vertex).
    fs::create_directories(dir / "small");
    for (int i = 0; i < 2; ++i) {
      const auto field = datasets::make_animated_field("pulsing_sphere", i / 4.0);
      datasets::write_vdb(*field, datasets::sample(*field, 24),
                          dir / ("small/s_" + std::to_string(i) + ".vdb"));
    }
    const auto r = run_isocurv({"features", "--time-series", dir / "small/s_*.vdb", "--radius",
                                "0.2", "--features", "LBE,H_ii", "-o", dir / "feat", "--json"},
                               300);
    ASSERT_TRUE(r.ok()) << r.describe();
    const nlohmann::json j = parse_json(r.out, "features series");
    ASSERT_EQ(j["entries"].size(), 2u);
    EXPECT_TRUE(j["entries"][1].contains("features"));
    EXPECT_EQ(io::read_pvd(dir / "feat/series.pvd").size(), 2u);
  }
}

// run over a series draws every frame with one colour range and one camera (--range shared, the
// default): the legends are the same pixels; with --range each they are not.
TEST(SeriesCli, RunPicturesShareOneRangeAcrossFrames) {
  TempDir dir("shared");
  auto run = [&](const std::string& out, const std::vector<std::string>& extra) {
    auto args = std::vector<std::string>{"run", "--time-series", frame_of("pulsing_sphere", 0),
                                         frame_of("pulsing_sphere", 4), "--color", "K",
                                         "--size", "200x150", "-o", dir / out, "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args, 300);
    EXPECT_TRUE(r.ok()) << r.describe();
  };
  run("shared", {});
  run("each", {"--range", "each"});
  auto png = [&](const std::string& out, int i) {
    const std::string f = "pulsing_sphere_" + std::to_string(i);
    return dir / (out + "/" + f + "/" + f + ".png");
  };
  EXPECT_EQ(test::legend_difference(png("shared", 0), png("shared", 4)), 0);
  EXPECT_GT(test::legend_difference(png("each", 0), png("each", 4)), 20);
  const nlohmann::json stats = parse_json(read_file(dir / "shared/pulsing_sphere_4/stats.json"), "stats");
  EXPECT_TRUE(stats.contains("picture")) << stats.dump();
}

TEST(SeriesCli, UsageErrors) {
  TempDir dir("usage");
  auto r = run_isocurv({"curvature", "--time-series", dir / "none_*.vdb", "-o", dir / "out"});
  EXPECT_EQ(r.exit_code, 1) << r.describe();
  expect_one_error_line(r, "no file matches");
  r = run_isocurv({"extract", "--time-series", frame_of("metaballs", 0), "--iso", "0.4,0.5", "-o",
                   dir / "out"});
  EXPECT_NE(r.exit_code, 0) << r.describe();
  expect_one_error_line(r, "--iso");
  // Several inputs without --time-series are a batch: its -o is a folder, not x.vtp.
  r = run_isocurv(
      {"lines", frame_of("metaballs", 0), frame_of("metaballs", 1), "-o", dir / "x.vtp"});
  EXPECT_NE(r.exit_code, 0) << r.describe();
  expect_one_error_line(r, "is a folder");
}

TEST(SeriesCli, PeakMemoryDoesNotGrowWithFrames) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's quarantine keeps freed frames resident: RSS measures it, not us";
#endif
  TempDir dir("memory");
  fs::create_directories(dir / "in");
  constexpr int n = 100;
  for (int i = 0; i < n; ++i) {
    const auto field = datasets::make_animated_field("metaballs", i / double(n));
    datasets::write_vdb(*field, datasets::sample(*field, 48),
                        dir / ("in/m_" + std::to_string(i) + ".vdb"));
  }
  const auto r = run_isocurv(
      {"curvature", "--time-series", dir / "in/m_*.vdb", "-o", dir / "out", "--json"}, 600);
  ASSERT_TRUE(r.ok()) << r.describe();
  const nlohmann::json j = parse_json(r.out, "series --json");
  ASSERT_EQ(j["entries"].size(), std::size_t(n));
  const double first = j["entries"][0]["peak_rss_kb"].get<double>();
  const double last = j["entries"][n - 1]["peak_rss_kb"].get<double>();
  std::printf("peak RSS after 1 frame %.1f MiB, after %d frames %.1f MiB (x%.3f)\n", first / 1024,
              n, last / 1024, last / first);
  EXPECT_LE(last, 1.2 * first) << "peak memory grew with the number of frames";
}

}  // namespace
}  // namespace isocurv::test
