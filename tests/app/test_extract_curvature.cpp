// isocurv extract and curvature end to end: every mesh format written by the CLI and read back
// in-process with io::read_mesh, arrays compared bit for bit across formats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cli.h"
#include "io/mesh_file.h"
#include "mc/mesh_check.h"
#include "mesh_compare.h"

using namespace isocurv;
using namespace isocurv::test;
using nlohmann::json;

namespace {

void expect_timings(const json& j, std::initializer_list<const char*> stages, const std::string& what) {
  ASSERT_TRUE(j.contains("timings_ms")) << what << "\n" << j.dump(2);
  const json& t = j["timings_ms"];
  ASSERT_TRUE(t.is_object()) << what;
  for (const char* s : stages) {
    ASSERT_TRUE(t.contains(s)) << what << ": timings_ms lacks \"" << s << "\"\n" << t.dump();
    EXPECT_TRUE(t[s].is_number()) << what << " " << s;
    EXPECT_GE(t[s].get<double>(), 0.0) << what << " " << s;
  }
}

double median(std::vector<float> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[v.size() / 2];
}

}  // namespace

TEST(CliExtract, EveryFormatHoldsTheSameFusedMesh) {
  TempDir dir("extract");
  std::vector<io::MeshFile> read;
  std::size_t json_vertices = 0, json_triangles = 0;
  for (const char* ext : {"vtp", "ply", "obj"}) {
    const std::string out = dir / (std::string("sphere.") + ext);
    const auto r = run_isocurv({"extract", dataset("sphere"), "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "extract --json");
    expect_timings(j, {"load", "extract", "write"}, std::string("extract --json ") + ext);
    EXPECT_EQ(j.value("output", ""), out);
    ASSERT_TRUE(fs::exists(out)) << out;
    read.push_back(io::read_mesh(out));
    const Mesh& m = read.back().mesh;
    EXPECT_EQ(m.positions.size(), j["vertices"].get<std::size_t>()) << ext;
    EXPECT_EQ(m.triangles.size(), j["triangles"].get<std::size_t>()) << ext;
    json_vertices = j["vertices"].get<std::size_t>();
    json_triangles = j["triangles"].get<std::size_t>();
    EXPECT_EQ(j["euler_characteristic"].get<long long>(), 2) << "sphere";
    EXPECT_TRUE(j["watertight"].get<bool>());
  }
  ASSERT_EQ(read.size(), 3u);
  EXPECT_GT(json_vertices, 1000u);
  EXPECT_GT(json_triangles, 2000u);
  expect_same_mesh(read[0].mesh, read[1].mesh, "vtp vs ply");
  expect_same_mesh(read[0].mesh, read[2].mesh, "vtp vs obj");
  // extract writes geometry only.
  EXPECT_TRUE(!read[0].field || read[0].field->k1.empty()) << "extract wrote curvature arrays";

  // The file itself is fused (DESIGN.md): no duplicates, closed, the sphere's Euler characteristic.
  const mc::MeshCheck c = mc::check_mesh(read[1].mesh);
  EXPECT_EQ(c.duplicate_vertices, 0u);
  EXPECT_EQ(c.unreferenced_vertices, 0u);
  EXPECT_TRUE(c.watertight());
  EXPECT_TRUE(c.oriented());
  EXPECT_EQ(c.euler, 2);
  // World space: the sphere has radius 0.8.
  double rmin = 1e9, rmax = 0;
  for (const Vec3f& p : read[0].mesh.positions) {
    const double r = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    rmin = std::min(rmin, r);
    rmax = std::max(rmax, r);
  }
  EXPECT_NEAR(rmin, 0.8, 0.02);
  EXPECT_NEAR(rmax, 0.8, 0.02);
}

TEST(CliExtract, TextAndQuietOutput) {
  TempDir dir("text");
  const auto r = run_isocurv({"extract", dataset("torus"), "-o", dir / "t.ply"});
  ASSERT_TRUE(r.ok()) << r.describe();
  EXPECT_EQ(r.out.rfind("wrote " + (dir / "t.ply"), 0), 0u) << r.out;
  EXPECT_NE(r.out.find("triangles"), std::string::npos) << r.out;
  const auto q = run_isocurv({"extract", dataset("torus"), "-o", dir / "q.ply", "--quiet"});
  ASSERT_TRUE(q.ok()) << q.describe();
  EXPECT_TRUE(q.out.empty()) << "--quiet printed: " << q.out;
  EXPECT_TRUE(q.err.empty()) << "--quiet printed: " << q.err;
  EXPECT_EQ(read_file(dir / "t.ply"), read_file(dir / "q.ply")) << "same input, same bytes (deterministic)";
}

TEST(CliExtract, ExplicitIsovalueMovesTheSurface) {
  TempDir dir("iso");
  // The sphere is |p| - 0.8: isovalue -0.3 is the sphere of radius 0.5.
  const auto r = run_isocurv({"extract", dataset("sphere"), "--iso", "-0.3", "-o", dir / "s.vtp", "--json"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const json j = parse_json(r.out, "extract --json");
  EXPECT_FLOAT_EQ(j["isovalue"].get<float>(), -0.3f);
  const Mesh m = io::read_mesh(dir / "s.vtp").mesh;
  ASSERT_FALSE(m.positions.empty());
  for (std::size_t i = 0; i < m.positions.size(); i += 97) {
    const Vec3f& p = m.positions[i];
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 0.5, 0.01);
  }
}

TEST(CliExtract, CapClosesASurfaceCutByTheBox) {
  TempDir dir("cap");
  // A raw float volume whose surface (x = 7.5) is cut by the box on four sides: a plane patch.
  const int n = 16;
  std::string bytes(std::size_t(n) * n * n * sizeof(float), '\0');
  float* v = reinterpret_cast<float*>(bytes.data());
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) *v++ = float(x);
  write_file(dir / "ramp.raw", bytes);
  const std::vector<std::string> raw = {"--dims", "16", "16", "16", "--type", "float", "--iso", "7.5", "--json"};
  auto args = raw;
  args.insert(args.begin(), {"check", dir / "ramp.raw"});
  const auto open = run_isocurv(args);
  ASSERT_TRUE(open.ok()) << open.describe();
  const json jo = parse_json(open.out, "check --json");
  EXPECT_FALSE(jo["watertight"].get<bool>());
  EXPECT_GT(jo["boundary_edges"].get<int>(), 0);
  EXPECT_EQ(jo["euler_characteristic"].get<int>(), 1) << "a disc";
  args.push_back("--cap");
  const auto capped = run_isocurv(args);
  ASSERT_TRUE(capped.ok()) << capped.describe();
  const json jc = parse_json(capped.out, "check --cap --json");
  EXPECT_TRUE(jc["watertight"].get<bool>()) << jc.dump(2);
  EXPECT_EQ(jc["euler_characteristic"].get<int>(), 2) << "a closed box";
  EXPECT_EQ(jc["duplicate_vertices"].get<int>(), 0);
}

TEST(CliCurvature, MeshAndVolumeNormalsOnTheSphere) {
  TempDir dir("normals");
  io::MeshFile files[2];
  const char* modes[2] = {"mesh", "volume"};
  for (int i = 0; i < 2; ++i) {
    const std::string out = dir / (std::string("s_") + modes[i] + ".vtp");
    const auto r = run_isocurv({"curvature", dataset("sphere"), "-o", out, "--normals", modes[i], "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "curvature --json");
    expect_timings(j, {"load", "extract", "curvature", "write"}, std::string("curvature --normals ") + modes[i]);
    if (i == 1) expect_timings(j, {"normals"}, "curvature --normals volume");
    EXPECT_EQ(j.value("normals", ""), modes[i]);
    ASSERT_TRUE(j.contains("curvature")) << j.dump(2);
    for (const char* q : {"H", "K", "k1", "k2"})
      for (const char* p : {"min", "max", "mean", "p1", "p5", "p25", "p50", "p75", "p95", "p99"})
        EXPECT_TRUE(j["curvature"][q][p].is_number()) << q << "." << p;
    // Solid sphere of radius 0.8: k1 = k2 = H = 1.25 and K = 1.5625, whichever way it was stored.
    EXPECT_NEAR(j["curvature"]["H"]["p50"].get<double>(), 1.25, 0.05) << modes[i];
    EXPECT_NEAR(j["curvature"]["K"]["p50"].get<double>(), 1.5625, 0.15) << modes[i];
    files[i] = io::read_mesh(out);
    ASSERT_TRUE(files[i].field.has_value()) << out;
    expect_complete_field(*files[i].field, files[i].mesh.positions.size(), out);
    EXPECT_EQ(files[i].mesh.positions.size(), j["vertices"].get<std::size_t>());
  }
  expect_same_mesh(files[0].mesh, files[1].mesh, "the same surface whatever the normals");
  EXPECT_FALSE(same_bits(files[0].field->normals, files[1].field->normals)) << "--normals volume changed nothing";
  // Volume normals are the gradient of |p| - 0.8: radial to float precision.
  const auto& P = files[1].mesh.positions;
  const auto& N = files[1].field->normals;
  double worst = 1;
  for (std::size_t v = 0; v < P.size(); ++v) {
    const double r = std::sqrt(double(P[v][0]) * P[v][0] + double(P[v][1]) * P[v][1] + double(P[v][2]) * P[v][2]);
    worst = std::min(worst, (P[v][0] * N[v][0] + P[v][1] * N[v][1] + P[v][2] * N[v][2]) / r);
  }
  EXPECT_GT(worst, 0.995) << "volume normals should be radial and outward";
}

TEST(CliCurvature, InsideBelowFlipsTheSign) {
  TempDir dir("inside");
  const auto above = run_isocurv({"curvature", dataset("torus"), "-o", dir / "a.vtp", "--json"});
  const auto below = run_isocurv({"curvature", dataset("torus"), "-o", dir / "b.vtp", "--inside", "below", "--json"});
  ASSERT_TRUE(above.ok()) << above.describe();
  ASSERT_TRUE(below.ok()) << below.describe();
  const json ja = parse_json(above.out, "curvature --json"), jb = parse_json(below.out, "curvature --json");
  // Torus R = 0.6, r = 0.25: H > 0 on most of it seen from the solid; K takes both signs.
  EXPECT_GT(ja["curvature"]["H"]["mean"].get<double>(), 0.5);
  EXPECT_LT(ja["curvature"]["K"]["min"].get<double>(), 0.0);
  EXPECT_GT(ja["curvature"]["K"]["max"].get<double>(), 0.0);
  EXPECT_NEAR(jb["curvature"]["H"]["mean"].get<double>(), -ja["curvature"]["H"]["mean"].get<double>(), 1e-3)
      << "--inside below: normals point the other way, H changes sign";
  EXPECT_NEAR(jb["curvature"]["K"]["mean"].get<double>(), ja["curvature"]["K"]["mean"].get<double>(), 1e-3)
      << "K does not depend on the orientation";
  EXPECT_EQ(ja["euler_characteristic"].get<int>(), 0);
  EXPECT_EQ(jb["euler_characteristic"].get<int>(), 0);
}

// One input, every format, and the files fed back in as inputs.
class CliFormats : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("formats");
    for (const char* ext : {"vtp", "ply"}) {
      // Mesh normals (the default on volumes is volume normals), so that re-estimating on the
      // mesh files read back can reproduce the arrays bit for bit.
      const auto r = run_isocurv({"curvature", dataset("torus"), "-o", *dir_ / (std::string("a.") + ext),
                                  "--normals", "mesh", "--quiet"});
      results_.push_back(r);
    }
    // .obj cannot hold the curvature arrays, so curvature refuses it; extract writes the geometry.
    results_.push_back(
        run_isocurv({"extract", dataset("torus"), "-o", *dir_ / "a.obj", "--quiet"}));
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
    results_.clear();
  }
  void SetUp() override {
    for (const auto& r : results_) ASSERT_TRUE(r.ok()) << r.describe();
  }
  static TempDir* dir_;
  static std::vector<CliResult> results_;
};
TempDir* CliFormats::dir_ = nullptr;
std::vector<CliResult> CliFormats::results_;

TEST_F(CliFormats, VtpAndPlyCarryEveryArrayBitForBit) {
  const io::MeshFile vtp = io::read_mesh(*dir_ / "a.vtp");
  const io::MeshFile ply = io::read_mesh(*dir_ / "a.ply");
  ASSERT_TRUE(vtp.field && ply.field);
  expect_complete_field(*vtp.field, vtp.mesh.positions.size(), "a.vtp");
  expect_same_mesh(vtp.mesh, ply.mesh, "vtp vs ply");
  expect_same_field(*vtp.field, *ply.field, "vtp vs ply");
  // Sanity of what was written: k1 >= k2, H = (k1 + k2) / 2, K = k1 k2 (float).
  const auto& f = *vtp.field;
  for (std::size_t i = 0; i < f.k1.size(); ++i) {
    ASSERT_GE(f.k1[i], f.k2[i]) << i;
    ASSERT_NEAR(f.H[i], 0.5f * (f.k1[i] + f.k2[i]), 1e-4f * (1 + std::abs(f.H[i]))) << i;
    ASSERT_NEAR(f.K[i], f.k1[i] * f.k2[i], 1e-3f * (1 + std::abs(f.K[i]))) << i;
  }
}

TEST_F(CliFormats, ObjFromExtractCarriesTheSameGeometry) {
  const io::MeshFile vtp = io::read_mesh(*dir_ / "a.vtp");
  const io::MeshFile obj = io::read_mesh(*dir_ / "a.obj");
  expect_same_mesh(vtp.mesh, obj.mesh, "vtp vs obj");
}

TEST_F(CliFormats, MeshInputsGiveTheSameCurvatureAsTheVolume) {
  // Re-estimating on the mesh read back (mesh normals, the default for mesh files) must reproduce
  // the arrays the volume run wrote with --normals mesh: lossless files, a deterministic
  // estimator, the same AO scale.
  const io::MeshFile ref = io::read_mesh(*dir_ / "a.vtp");
  ASSERT_TRUE(ref.field);
  for (const char* in : {"a.vtp", "a.ply", "a.obj"}) {
    const std::string out = *dir_ / (std::string("from_") + in + ".ply");
    const auto r = run_isocurv({"curvature", *dir_ / in, "-o", out, "--json"});
    ASSERT_TRUE(r.ok()) << r.describe();
    const json j = parse_json(r.out, "curvature --json");
    expect_timings(j, {"load", "curvature", "write"}, std::string("curvature ") + in);
    EXPECT_FALSE(j["timings_ms"].contains("extract")) << "a mesh input is not extracted";
    const io::MeshFile again = io::read_mesh(out);
    ASSERT_TRUE(again.field);
    expect_same_mesh(ref.mesh, again.mesh, std::string("from ") + in);
    expect_same_field(*ref.field, *again.field, std::string("from ") + in);
  }
}

TEST_F(CliFormats, VolumeNormalsNeedAVolume) {
  const std::string out = *dir_ / "nope.vtp";
  const auto r = run_isocurv({"curvature", *dir_ / "a.vtp", "--normals", "volume", "-o", out});
  expect_clean_failure(r, "--normals volume");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliCurvature, TorusOuterEquatorPrincipalCurvatures) {
  // Outer equator of the torus (R = 0.6, r = 0.25 at isovalue 0; the torus .vdb is a density, so
  // without --iso the suggested (Otsu) isovalue gives a fatter tube): k1 = 1/r = 4,
  // k2 = 1/(R + r) = 1.176...
  TempDir dir("torus");
  const auto r = run_isocurv(
      {"curvature", dataset("torus"), "--iso", "0", "-o", dir / "t.vtp", "--normals", "volume", "--quiet"});
  ASSERT_TRUE(r.ok()) << r.describe();
  const io::MeshFile f = io::read_mesh(dir / "t.vtp");
  ASSERT_TRUE(f.field);
  std::vector<float> k1, k2;
  for (std::size_t i = 0; i < f.mesh.positions.size(); ++i) {
    const Vec3f& p = f.mesh.positions[i];
    const double rho = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1]);
    if (rho > 0.84 && std::abs(p[2]) < 0.05) {
      k1.push_back(f.field->k1[i]);
      k2.push_back(f.field->k2[i]);
    }
  }
  ASSERT_GT(k1.size(), 20u);
  EXPECT_NEAR(median(k1), 4.0, 0.1);
  EXPECT_NEAR(median(k2), 1.0 / 0.85, 0.05);
}
