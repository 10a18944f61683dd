// --device reference: the C++ references (mc::extract_reference, curvature::estimate_reference) as
// a device every compute command takes, equal to the OpenCL device up to vertex order and float
// precision; and what a machine without any OpenCL platform is told.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "cli.h"
#include "io/mesh_file.h"
#include "tests/mc/same_mesh.h"

using namespace isocurv::test;
using isocurv::Mesh;
using isocurv::Tri;

namespace {

/// For each vertex of `a`, the vertex of `b` at the same position (within `tol` on every axis);
/// records a failure and returns an empty map when some vertex has no twin.
std::vector<std::uint32_t> match_vertices(const Mesh& a, const Mesh& b, float tol) {
  std::vector<std::uint32_t> by_x(b.positions.size());
  std::iota(by_x.begin(), by_x.end(), 0u);
  std::sort(by_x.begin(), by_x.end(),
            [&](auto i, auto j) { return b.positions[i][0] < b.positions[j][0]; });
  std::vector<std::uint32_t> map(a.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    const auto& p = a.positions[i];
    auto it = std::lower_bound(by_x.begin(), by_x.end(), p[0] - tol,
                               [&](std::uint32_t j, float x) { return b.positions[j][0] < x; });
    int found = -1, count = 0;
    for (; it != by_x.end() && b.positions[*it][0] <= p[0] + tol; ++it) {
      const auto& q = b.positions[*it];
      if (std::fabs(q[1] - p[1]) <= tol && std::fabs(q[2] - p[2]) <= tol) {
        found = int(*it);
        ++count;
      }
    }
    if (count != 1) {
      ADD_FAILURE() << "vertex " << i << " has " << count << " twins";
      return {};
    }
    map[i] = std::uint32_t(found);
  }
  return map;
}

/// The same surface: same vertices (up to order) and the same triangles with the same winding.
void expect_same_surface(const Mesh& a, const Mesh& b,
                         std::vector<std::uint32_t>* map_out = nullptr) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  ASSERT_FALSE(a.triangles.empty());
  float scale = 1;  // float rounding grows with the coordinates' size
  for (const auto& p : b.positions)
    scale = std::max({scale, std::fabs(p[0]), std::fabs(p[1]), std::fabs(p[2])});
  const auto map = match_vertices(a, b, 1e-6f * scale);
  ASSERT_EQ(map.size(), a.positions.size());
  expect_same_triangles(a, b, map);
  if (map_out) *map_out = map;
}

}  // namespace

TEST(ReferenceDevice, ExtractEqualsTheOpenClDevice) {
  TempDir dir("extract");
  for (const char* cap : {"", "--cap"}) {
    std::vector<std::string> args = {"extract", dataset("torus"), "--quiet"};
    if (*cap) args.push_back(cap);
    auto cl = args, ref = args;
    cl.insert(cl.end(), {"-o", dir / "cl.ply"});
    ref.insert(ref.end(), {"-o", dir / "ref.ply", "--device", "reference"});
    const auto a = run_isocurv(cl), b = run_isocurv(ref);
    ASSERT_TRUE(a.ok()) << a.describe();
    ASSERT_TRUE(b.ok()) << b.describe();
    expect_same_surface(isocurv::io::read_mesh(dir / "ref.ply").mesh,
                        isocurv::io::read_mesh(dir / "cl.ply").mesh);
  }
}

TEST(ReferenceDevice, CurvatureAgreesWithTheOpenClDevice) {
  TempDir dir("curvature");
  // One mesh for both, so only the curvature stage differs (each device's own extraction rounds
  // positions its own way, which slivers amplify).
  ASSERT_TRUE(run_isocurv({"extract", dataset("sphere"), "-o", dir / "m.ply", "--quiet"}).ok());
  const auto a = run_isocurv({"curvature", dir / "m.ply", "-o", dir / "cl.vtp", "--quiet"});
  const auto b = run_isocurv(
      {"curvature", dir / "m.ply", "-o", dir / "ref.vtp", "--device", "reference", "--json"});
  ASSERT_TRUE(a.ok()) << a.describe();
  ASSERT_TRUE(b.ok()) << b.describe();
  EXPECT_NE(parse_json(b.out, "curvature --json").value("device", "").find("reference"),
            std::string::npos)
      << b.out;
  const auto cl = isocurv::io::read_mesh(dir / "cl.vtp"),
             ref = isocurv::io::read_mesh(dir / "ref.vtp");
  ASSERT_EQ(cl.mesh.positions.size(), ref.mesh.positions.size());
  ASSERT_TRUE(cl.field && ref.field);
  // Float kernels against the double reference: the RMS of the differences of H and K relative
  // to their RMS (the kernel tests' measure) and of the worst vertex.
  double dh = 0, h = 0, dk = 0, k = 0, worst = 0;
  for (std::size_t i = 0; i < cl.mesh.positions.size(); ++i) {
    const double hr = ref.field->H[i], hc = cl.field->H[i], kr = ref.field->K[i],
                 kc = cl.field->K[i];
    dh += (hr - hc) * (hr - hc);
    h += hr * hr;
    dk += (kr - kc) * (kr - kc);
    k += kr * kr;
    worst = std::max(worst, std::fabs(hr - hc) / (std::fabs(hr) + 1e-3));
  }
  EXPECT_LT(std::sqrt(dh / h), 1e-4);
  EXPECT_LT(std::sqrt(dk / k), 1e-4);
  EXPECT_LT(worst, 1e-2);
}

TEST(ReferenceDevice, EveryComputeCommandTakesIt) {
  TempDir dir("commands");
  const std::vector<std::string> ref = {"--device", "reference"};
  auto with = [&](std::vector<std::string> a) {
    a.insert(a.end(), ref.begin(), ref.end());
    return a;
  };
  const auto run = run_isocurv(
      with({"run", dataset("torus"), "--size", "64x64", "-o", dir / "out", "--quiet"}), 120);
  ASSERT_TRUE(run.ok()) << run.describe();
  const auto stats = parse_json(read_file(dir / "out/stats.json"), "stats.json");
  EXPECT_NE(stats.value("device", "").find("reference"), std::string::npos) << stats.dump();
  const auto render =
      run_isocurv(with({"render", dataset("torus"), "--size", "64x64", "-o", dir / "t.png"}), 120);
  ASSERT_TRUE(render.ok()) << render.describe();
  EXPECT_EQ(png_size(dir / "t.png"), (std::array<std::uint32_t, 2>{64, 64}));
  const auto check = run_isocurv(with({"check", dataset("torus"), "--json"}));
  ASSERT_TRUE(check.ok()) << check.describe();
  EXPECT_TRUE(parse_json(check.out, "check --json")["watertight"].is_boolean());
  // The environment chooses it too.
  const auto env = run_isocurv({"extract", dataset("torus"), "-o", dir / "e.ply", "--json"}, 60,
                               {"ISOCURV_DEVICE=reference"});
  ASSERT_TRUE(env.ok()) << env.describe();
  EXPECT_NE(parse_json(env.out, "extract --json").value("device", "").find("reference"),
            std::string::npos);
}

TEST(ReferenceDevice, DevicesShowsItAsTheDefaultFromTheEnvironment) {
  // Device::open rejected ISOCURV_DEVICE=reference as "not a device number".
  const auto r = run_isocurv({"devices", "--json"}, 60, {"ISOCURV_DEVICE=reference"});
  ASSERT_TRUE(r.ok()) << r.describe();
  for (const auto& d : parse_json(r.out, "devices --json"))
    EXPECT_FALSE(d["default"].get<bool>()) << d.dump();
  const auto text = run_isocurv({"devices"}, 60, {"ISOCURV_DEVICE=reference"});
  ASSERT_TRUE(text.ok()) << text.describe();
  EXPECT_NE(text.out.find("the default is the C++ reference"), std::string::npos) << text.out;
}

TEST(NoOpenCl, TheMessageNamesThePackagesAndTheReference) {
  TempDir dir("noopencl");
  // ocl-icd reads its driver list from OCL_ICD_VENDORS: a folder that does not exist has none.
  const std::vector<std::string> none = {"OCL_ICD_VENDORS=/nonexistent"};
  for (const char* cmd : {"extract", "curvature"}) {
    const auto r = run_isocurv({cmd, dataset("sphere"), "-o", dir / "o.ply"}, 60, none);
    expect_clean_failure(r, "no OpenCL platform");
    EXPECT_NE(r.err.find("pocl-opencl-icd"), std::string::npos) << r.describe();
    EXPECT_NE(r.err.find("--device reference"), std::string::npos) << r.describe();
  }
  expect_clean_failure(run_isocurv({"devices"}, 60, none), "pocl-opencl-icd");
  // ... and the reference works there.
  const auto ok = run_isocurv(
      {"curvature", dataset("sphere"), "--device", "reference", "-o", dir / "o.ply", "--quiet"}, 60,
      none);
  ASSERT_TRUE(ok.ok()) << ok.describe();
  EXPECT_FALSE(isocurv::io::read_mesh(dir / "o.ply").mesh.triangles.empty());
}
