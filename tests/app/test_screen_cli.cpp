// isocurv screen end to end: a volume and a mesh file to PNG and .vti, the empty isovalue, the
// size limit and the options that cannot apply.
#include <gtest/gtest.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include "tests/app/cli.h"
#include "tests/viz/png_stats.h"
#include "viz/curvature_scene.h"

namespace isocurv::test {
namespace {

using json = nlohmann::json;

TEST(CliScreen, VolumeToPictureAndRawImage) {
  TempDir dir("screen_volume");
  const auto r = run_isocurv({"screen", dataset("sphere"), "--size", "320x240", "--edges", "3",
                              "-o", dir / "s.png", "--raw", dir / "s.vti", "--json", "--quiet"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_EQ(j["producer"], "ray cast");
  EXPECT_GT(j["estimated_pixels"].get<int>(), 5000);
  EXPECT_FALSE(j["empty"].get<bool>());
  EXPECT_NEAR(j["median_H"].get<double>(), 1 / 0.8, 0.02);  // the sphere's R = 0.8
  EXPECT_NEAR(j["median_K"].get<double>(), 1 / 0.64, 0.04);
  EXPECT_TRUE(j["timings_ms"].contains("cast")) << j.dump(2);
  EXPECT_EQ(png_size(dir / "s.png"), (std::array<std::uint32_t, 2>{320, 240}));
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "s.vti").c_str());
  reader->Update();
  vtkImageData* img = reader->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  // The .vti is in the picture's pixel grid: as large as the PNG, point (x, y) its pixel (x, y)
  // from the bottom-left; the estimated pixels are where the PNG shows the surface.
  EXPECT_EQ(dims[0], 320);
  EXPECT_EQ(dims[1], 240);
  EXPECT_LT(j["image"]["width"].get<int>(), 320);  // the surface box, left of the legend
  auto* valid = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("Valid"));
  auto* h = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("H"));
  ASSERT_TRUE(valid && h && img->GetPointData()->GetArray("K"));
  const Pixels png = read_pixels(dir / "s.png");
  ASSERT_EQ(png.width, 320);
  long n = 0, on_background = 0;
  for (vtkIdType i = 0; i < valid->GetNumberOfTuples(); ++i)
    if (valid->GetValue(i) == 1) {
      ++n;
      EXPECT_GT(h->GetValue(i), 0.5);
      const int x = int(i % 320), y = int(i / 320);
      const double t = double(y) / 239;
      const unsigned char* p = png.at(x, y);
      bool bg = true;
      for (int c = 0; c < 3; ++c)
        bg = bg && std::abs(p[c] - 255 * (viz::kBackgroundBottom[c] +
                                          t * (viz::kBackgroundTop[c] - viz::kBackgroundBottom[c]))) < 6;
      on_background += bg;
    }
  EXPECT_EQ(n, j["estimated_pixels"].get<long>());
  EXPECT_LT(on_background, n / 100) << "the .vti's surface is not where the PNG's is";
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"s.png", "s.vti"}));
  // The picture's size as written, in --json and in the line without it.
  EXPECT_EQ(j["picture"]["width"], 320);
  EXPECT_EQ(j["picture"]["height"], 240);
  const auto line = run_isocurv({"screen", dataset("sphere"), "--size", "320x240", "-o", dir / "t.png"}, 120);
  ASSERT_TRUE(line.ok()) << line.describe();
  EXPECT_NE(line.out.find("t.png (320x240)"), std::string::npos) << line.out;
}

// The interquartile spread of H over the estimated pixels of a --raw image.
double h_spread(const std::string& vti) {
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(vti.c_str());
  reader->Update();
  auto* pd = reader->GetOutput()->GetPointData();
  auto* valid = vtkFloatArray::SafeDownCast(pd->GetArray("Valid"));
  auto* h = vtkFloatArray::SafeDownCast(pd->GetArray("H"));
  std::vector<float> v;
  for (vtkIdType i = 0; valid && h && i < valid->GetNumberOfTuples(); ++i)
    if (valid->GetValue(i) == 1 && std::isfinite(h->GetValue(i))) v.push_back(h->GetValue(i));
  if (v.size() < 100) return -1;
  std::sort(v.begin(), v.end());
  return v[v.size() * 3 / 4] - v[v.size() / 4];
}

// On integer data the default smoothing comes from the data (the volume estimator's noise
// scale): a noisy 8-bit ball's H no longer shows the quantised steps pixel by pixel, where
// --smooth 0 keeps them; float data is not smoothed by default.
TEST(CliScreen, IntegerDataIsSmoothedFromItsNoiseByDefault) {
  TempDir dir("screen_smooth");
  const double R = 16;
  const std::string ball = write_ct_ball(dir.path(), 48, R, 8, 99, 0.3);
  auto cast = [&](const std::vector<std::string>& extra, const std::string& name) {
    std::vector<std::string> args = {"screen", ball, "--iso", "120", "--size", "320x240", "-o",
                                     dir / (name + ".png"), "--raw", dir / (name + ".vti"), "--json", "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_isocurv(args, 120);
    EXPECT_TRUE(r.ok()) << r.describe();
    return parse_json(r.out, "screen --json");
  };
  const json a = cast({}, "auto"), z = cast({"--smooth", "0"}, "none");
  EXPECT_GT(a["smoothing_voxels"].get<double>(), 0.8) << a.dump(2);
  EXPECT_EQ(z["smoothing_voxels"].get<double>(), 0.0);
  EXPECT_NEAR(a["median_H"].get<double>(), 1 / R, 0.1 / R);
  const double sa = h_spread(dir / "auto.vti"), sz = h_spread(dir / "none.vti");
  ASSERT_GT(sa, 0);
  EXPECT_LT(sa, 0.5 * sz) << "the default left the quantised steps in H";
  const auto f = run_isocurv({"screen", dataset("torus"), "--size", "160x120", "-o", dir / "t.png", "--json", "--quiet"}, 120);
  ASSERT_TRUE(f.ok()) << f.describe();
  EXPECT_EQ(parse_json(f.out, "screen --json")["smoothing_voxels"].get<double>(), 0.0) << "float data";
  const auto bad = run_isocurv({"screen", ball, "-o", dir / "b.png", "--smooth", "7"}, 60);
  EXPECT_EQ(bad.exit_code, 2) << "a usage error";
  EXPECT_NE(bad.err.find("--smooth"), std::string::npos) << bad.err;
}

// screen frames a volume as render does (on its surface, not its box): the box of the pixels
// that see the surface (the .vti's Valid, in the picture's grid) is the render's surface box.
TEST(CliScreen, FramedAsRenderFramesTheSameVolume) {
  TempDir dir("screen_framing");
  for (const std::vector<std::string>& cmd :
       {std::vector<std::string>{"screen", dataset("torus"), "-o", dir / "s.png", "--raw", dir / "s.vti"},
        std::vector<std::string>{"render", dataset("torus"), "-o", dir / "r.png"}}) {
    std::vector<std::string> args = cmd;
    args.insert(args.end(), {"--size", "320x240", "--quiet"});
    const auto r = run_isocurv(args, 120);
    ASSERT_TRUE(r.ok()) << r.describe();
  }
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "s.vti").c_str());
  reader->Update();
  auto* valid = vtkFloatArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetArray("Valid"));
  ASSERT_TRUE(valid);
  Box s{320, 240, 0, 0};
  for (vtkIdType i = 0; i < valid->GetNumberOfTuples(); ++i)
    if (valid->GetValue(i) == 1) {
      const int x = int(i % 320), y = int(i / 320);
      s.x0 = std::min(s.x0, x), s.y0 = std::min(s.y0, y);
      s.x1 = std::max(s.x1, x + 1), s.y1 = std::max(s.y1, y + 1);
    }
  const std::vector<Box> skip = {{int(0.8 * 320), 0, 320, 240}, {0, int(0.88 * 240), 320, 240}};
  const Box r = foreground_box(dir / "r.png", viz::kBackgroundBottom, viz::kBackgroundTop, skip);
  // The ray cast loses a few pixels where rays graze the torus' lower rim (under 4% of the
  // height); the box-framed picture of before was 40% smaller.
  for (auto [a, b, tol] : {std::tuple{s.x0, r.x0, 4}, {s.x1, r.x1, 4}, {s.y0, r.y0, 9}, {s.y1, r.y1, 4}})
    EXPECT_NEAR(a, b, tol) << "screen " << s.x0 << " " << s.y0 << " " << s.x1 << " " << s.y1
                         << ", render " << r.x0 << " " << r.y0 << " " << r.x1 << " " << r.y1;
}

// A sparse .vdb whose active box holds over 2^28 voxels (a ball and one voxel 1100 away) is cast
// through its leaves, not refused; --smooth, which needs the dense copy, is refused in one line.
TEST(CliScreen, ALargeSparseVdbIsCastThroughItsLeaves) {
  TempDir dir("screen_sparse");
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      20.0f, openvdb::Vec3f(30, 40, 50), 1.0f, 3.0f);
  grid->tree().setValueOn(openvdb::Coord(1100, 1100, 1100), grid->background());
  grid->setName("ball");
  openvdb::io::File(dir / "big.vdb").write({grid});
  const auto r = run_isocurv({"screen", dir / "big.vdb", "--iso", "0", "--size", "200x150",
                              "-o", dir / "big.png", "--json", "--quiet"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_GT(j["estimated_pixels"].get<int>(), 2000);
  EXPECT_NEAR(j["median_H"].get<double>(), 1 / 20.0, 0.05 / 20);
  const auto smooth = run_isocurv({"screen", dir / "big.vdb", "--iso", "0", "--smooth", "1",
                                   "-o", dir / "smooth.png"});
  expect_clean_failure(smooth, "smoothing");
  EXPECT_FALSE(fs::exists(dir / "smooth.png"));
}

TEST(CliScreen, SmoothingKeepsTheSphereAndIsReportedAndBounded) {
  // A smooth sphere smoothed by 2 voxels: H stays 1/R within the shrinkage (sigma^2 H, about 1%
  // of R here); --json and the title say so; widths outside [0, 6] voxels are usage errors.
  TempDir dir("screen_smooth");
  const auto r = run_isocurv({"screen", dataset("sphere"), "--size", "320x240", "--smooth", "2",
                              "-o", dir / "s.png", "--json", "--quiet"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_EQ(j["smoothing_voxels"].get<double>(), 2.0);
  EXPECT_TRUE(j["timings_ms"].contains("smooth")) << j.dump(2);
  EXPECT_NEAR(j["median_H"].get<double>(), 1 / 0.8, 0.05);
  for (const char* bad : {"-1", "7"}) {
    const auto e = run_isocurv({"screen", dataset("sphere"), "--smooth", bad, "-o", dir / "x.png"});
    EXPECT_EQ(e.exit_code, 2) << bad << ": " << e.describe();
    const auto v = run_isocurv({"view", dataset("sphere"), "--screen-smooth", bad});
    EXPECT_EQ(v.exit_code, 2) << bad << ": " << v.describe();
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"s.png"}));
}

TEST(CliScreen, MeshFileAndMellado) {
  TempDir dir("screen_mesh");
  ASSERT_TRUE(run_isocurv({"extract", dataset("torus"), "-o", dir / "t.ply", "--quiet"}).ok());
  const auto r = run_isocurv({"screen", dir / "t.ply", "--size", "300x300", "--estimator",
                              "mellado", "-o", dir / "t.png", "--json", "--quiet"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_EQ(j["producer"], "rasterised mesh");
  EXPECT_GT(j["estimated_pixels"].get<int>(), 5000);
  EXPECT_FALSE(j.contains("median_K"));
  const auto k = run_isocurv(
      {"screen", dir / "t.ply", "--estimator", "mellado", "--color", "K", "-o", dir / "k.png"});
  EXPECT_EQ(k.exit_code, 1) << k.describe();
  ASSERT_EQ(k.err_lines().size(), 1u) << k.describe();
  EXPECT_EQ(k.err_lines()[0].rfind("isocurv:", 0), 0u);
  const auto iso = run_isocurv({"screen", dir / "t.ply", "--iso", "0.5", "-o", dir / "i.png"});
  EXPECT_NE(iso.exit_code, 0);
}

// A curvature file's own normals (the smooth surface's) rasterised give the ray cast's
// curvature: the bundled sphere (R 0.8) at median H R = 1.00 within 1% (its face normals gave
// 0.86).
TEST(CliScreen, ACurvatureFileIsRasterisedWithItsOwnNormals) {
  TempDir dir("screen_normals");
  ASSERT_TRUE(run_isocurv({"curvature", dataset("sphere"), "-o", dir / "s.vtp", "--quiet"}).ok());
  const auto r = run_isocurv({"screen", dir / "s.vtp", "--size", "400x400", "-o", dir / "s.png",
                              "--json", "--quiet"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_EQ(j["producer"], "rasterised mesh");
  EXPECT_NEAR(j["median_H"].get<double>() * 0.8, 1.0, 0.01) << j.dump();
}

TEST(CliScreen, AnIsovalueThatMissesGivesAnEmptyImageAndAWarning) {
  TempDir dir("screen_empty");
  const auto r = run_isocurv({"screen", dataset("torus"), "--iso", "100", "--size", "64x64", "-o",
                              dir / "e.png", "--json"},
                             120);
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "screen --json");
  EXPECT_TRUE(j["empty"].get<bool>());
  EXPECT_EQ(j["estimated_pixels"].get<int>(), 0);
  ASSERT_EQ(r.err_lines().size(), 1u) << r.describe();
  EXPECT_NE(r.err_lines()[0].find("warning"), std::string::npos);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"e.png"});
}

TEST(CliScreen, SizeLimitAndBadOutputsAreOneErrorLine) {
  TempDir dir("screen_bad");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"screen", dataset("torus"), "--size", "9000x100", "-o",
                                 dir / "a.png"},
        std::vector<std::string>{"screen", dataset("torus"), "-o", dir / "a.jpg"},
        std::vector<std::string>{"screen", dataset("torus"), "-o", dir / "a.png", "--raw",
                                 dir / "a.vtp"},
        std::vector<std::string>{"screen", dataset("torus"), "--edges", "4", "-o", dir / "a.png"},
        std::vector<std::string>{"screen", dir / "missing.vdb", "-o", dir / "a.png"}}) {
    const auto r = run_isocurv(args);
    EXPECT_NE(r.exit_code, 0) << r.describe();
    EXPECT_FALSE(r.timed_out);
    ASSERT_EQ(r.err_lines().size(), 1u) << "one error line, exactly: " << r.describe();
    EXPECT_EQ(r.err_lines()[0].rfind("isocurv:", 0), 0u) << r.describe();
  }
  EXPECT_TRUE(dir.entries().empty());
  EXPECT_TRUE(run_isocurv({"screen", "--help"}).out.find("Example: isocurv screen") !=
              std::string::npos);
}

}  // namespace
}  // namespace isocurv::test
