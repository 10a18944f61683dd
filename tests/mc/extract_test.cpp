// The device mesher against the reference mesher and topological invariants.
#include <gtest/gtest.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <random>

#include "core/cl_device.h"
#include "mc/bricks.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "tests/mc/same_mesh.h"
#include "tests/mc/volumes.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

Device& dev() { return Device::default_device(); }

mc::Options keys() {
  mc::Options o;
  o.keep_edge_keys = true;
  return o;
}

using test::expect_same_mesh;

void expect_closed(const Mesh& m, long long euler) {
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_GT(c.triangles, 0u);
  EXPECT_EQ(c.duplicate_vertices, 0u);
  EXPECT_EQ(c.unreferenced_vertices, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_EQ(c.boundary_edges, 0u);
  EXPECT_EQ(c.non_manifold_edges, 0u);
  EXPECT_EQ(c.misoriented_edges, 0u);
  EXPECT_EQ(c.euler, euler);
}

// 23x19x29 voxels of uniform noise in [-1, 1] (every case occurs at isovalue 0).
volume::Volume noise_volume(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> noise(23 * 19 * 29);
  for (auto& x : noise) x = u(rng);
  std::size_t i = 0;
  return test::sampled([&](double, double, double) { return noise[i++]; }, {23, 19, 29});
}

// A sparse VDB level set (negative inside, narrow band, tiles inside) across many leaves.
volume::Volume level_set_sphere() {
  volume::Volume ls;
  ls.grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(10.0f, openvdb::Vec3f(0.3f, -0.2f, 0.1f), 0.5f);
  ls.dense = false;
  ls.inside = volume::Inside::Below;
  ls.domain = ls.grid->evalActiveVoxelBoundingBox();
  ls.stats.min = -1.5;
  ls.stats.max = 1.5;
  return ls;
}

bool bit_identical(const Mesh& a, const Mesh& b) {
  return a.positions.size() == b.positions.size() && a.triangles.size() == b.triangles.size() &&
         std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(Vec3f)) == 0 &&
         std::memcmp(a.triangles.data(), b.triangles.data(), a.triangles.size() * sizeof(Tri)) == 0;
}

}  // namespace

TEST(Extract, SphereMatchesReferenceAndIsClosedWithOutwardNormals) {
  auto v = test::ball(40, 14.3, 19.7);
  Mesh m = mc::extract(v, 0.0f, dev(), keys());
  expect_same_mesh(m, mc::extract_reference(v, 0.0f, keys()));
  expect_closed(m, 2);
  // Every triangle's normal points away from the centre.
  for (const Tri& t : m.triangles) {
    const Vec3f &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
    double u[3], w[3], g[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = b[k] - a[k];
      w[k] = c[k] - a[k];
      g[k] = (a[k] + b[k] + c[k]) / 3.0 - 19.7;
    }
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    ASSERT_GT(n[0] * g[0] + n[1] * g[1] + n[2] * g[2], 0.0);
  }
}

TEST(Extract, LevelSetNormalsAlsoPointOutward) {
  // Inside below: the same ball as a signed distance (negative inside) gives the same surface.
  auto v = test::sampled([](double x, double y, double z) {
    return float(std::sqrt((x - 15) * (x - 15) + (y - 15) * (y - 15) + (z - 15) * (z - 15)) - 9.5);
  }, {31, 31, 31}, {1, 1, 1}, {0, 0, 0}, volume::Inside::Below);
  Mesh m = mc::extract(v, 0.0f, dev());
  expect_closed(m, 2);
  const mc::MeshCheck c = mc::check_mesh(m);
  double vol = 0;  // signed volume > 0 when normals point out
  for (const Tri& t : m.triangles) {
    const Vec3f &a = m.positions[t[0]], &b = m.positions[t[1]], &d = m.positions[t[2]];
    vol += (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0])) / 6;
  }
  EXPECT_NEAR(vol, 4.0 / 3.0 * M_PI * 9.5 * 9.5 * 9.5, 0.03 * vol);
  EXPECT_GT(c.area, 0);
}

TEST(Extract, TorusAndDoubleTorusHaveTheirEulerCharacteristic) {
  auto torus = test::sampled([](double x, double y, double z) {
    return test::torus_density(x - 24, y - 24, z - 12, 14, 5);
  }, {48, 48, 24});
  Mesh m = mc::extract(torus, 0.0f, dev(), keys());
  expect_same_mesh(m, mc::extract_reference(torus, 0.0f, keys()));
  expect_closed(m, 0);
  auto two = test::sampled([](double x, double y, double z) {
    return std::max(test::torus_density(x - 20, y - 20, z - 12, 10, 4),
                    test::torus_density(x - 38, y - 20, z - 12, 10, 4));
  }, {60, 40, 24});
  expect_closed(mc::extract(two, 0.0f, dev()), -2);
}

TEST(Extract, CappedGyroidIsClosedAndMatchesReference) {
  auto g = test::sampled([](double x, double y, double z) {
    const double s = 2 * M_PI / 20;
    return float(std::sin(s * x) * std::cos(s * y) + std::sin(s * y) * std::cos(s * z) + std::sin(s * z) * std::cos(s * x));
  }, {41, 37, 45});
  mc::Options o = keys();
  Mesh open = mc::extract(g, 0.1f, dev(), o);
  expect_same_mesh(open, mc::extract_reference(g, 0.1f, o));
  EXPECT_GT(mc::check_mesh(open).boundary_edges, 0u);  // cut by the box, left open as VTK does
  o.cap = true;
  Mesh closed = mc::extract(g, 0.1f, dev(), o);
  expect_same_mesh(closed, mc::extract_reference(g, 0.1f, o));
  const mc::MeshCheck c = mc::check_mesh(closed);
  EXPECT_TRUE(c.watertight());
  EXPECT_TRUE(c.oriented());
  EXPECT_EQ(c.duplicate_vertices, 0u);
  EXPECT_EQ(c.euler % 2, 0);
}

TEST(Extract, CapsLieOnTheVolumesBox) {
  // A ball cut by every face of its box: cap vertices sit a 1/1024 voxel off the box at most (they
  // once sat up to half a voxel outside it), snapped or not.
  auto v = test::ball(16, 9.5, 7.5);
  for (float snap : {0.0f, mc::kDefaultSnap}) {
    mc::Options o;
    o.cap = true;
    o.snap = snap;
    const Mesh m = mc::extract(v, 0.0f, dev(), o);
    expect_closed(m, 2);
    const float slack = mc::kMinEdgeFraction * 1.0001f;
    std::size_t on_box = 0;
    for (const Vec3f& p : m.positions)
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(p[k], -slack) << snap;
        ASSERT_LE(p[k], 15 + slack) << snap;
        on_box += p[k] <= slack || p[k] >= 15 - slack;
      }
    EXPECT_GT(on_box, 100u);
  }
}

TEST(Extract, RandomNoiseMatchesReferenceWithEveryCase) {
  auto v = noise_volume(7);
  mc::Options o = keys();
  o.cap = true;
  Mesh m = mc::extract(v, 0.0f, dev(), o);
  expect_same_mesh(m, mc::extract_reference(v, 0.0f, o));
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_TRUE(c.watertight());
  EXPECT_TRUE(c.oriented());
  EXPECT_EQ(c.duplicate_vertices, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
}

TEST(Extract, BrickSeamsInEveryDirectionLeaveNoCracksOrDuplicates) {
  // A ball centred on a brick corner (16,16,16) crosses seams along x, y and z.
  auto v = test::ball(33, 11.0, 16.0);
  Mesh m = mc::extract(v, 0.0f, dev(), keys());
  expect_same_mesh(m, mc::extract_reference(v, 0.0f, keys()));
  expect_closed(m, 2);
  const volume::Volume ls = level_set_sphere();
  Mesh s = mc::extract(ls, 0.0f, dev(), keys());
  expect_same_mesh(s, mc::extract_reference(ls, 0.0f, keys()));
  expect_closed(s, 2);
}

TEST(Extract, WithoutEdgeKeysTheOutputIsTheSame) {
  // The tests above compare against the reference with edge keys on, which sends every vertex
  // through mc_emit's general path; without keys, cells inside the frame take the branch-free
  // one. Both must give the same mesh, bit for bit (and so the reference's).
  const auto random = noise_volume(5);
  const volume::Volume ls = level_set_sphere();
  const auto ball = test::ball(33, 11.0, 16.0);
  for (bool cap : {false, true}) {
    mc::Options plain, with_keys = keys();
    plain.cap = with_keys.cap = cap;
    for (const volume::Volume* v : std::vector<const volume::Volume*>{&random, &ball, &ls}) {
      const Mesh a = mc::extract(*v, 0.0f, dev(), plain), b = mc::extract(*v, 0.0f, dev(), with_keys);
      EXPECT_GT(a.triangles.size(), 0u);
      EXPECT_TRUE(bit_identical(a, b)) << (v == &random ? "noise" : v == &ball ? "ball" : "level set")
                                       << (cap ? ", capped" : "");
    }
  }
}

TEST(Extract, NarrowHashGivesIdenticalOutput) {
  auto torus = test::sampled([](double x, double y, double z) {
    return test::torus_density(x - 20, y - 20, z - 10, 12, 4);
  }, {40, 40, 20});
  Mesh full = mc::extract(torus, 0.0f, dev());
  for (int bits : {1, 3, 5, 8, 10, 13}) {  // runs wider than the hash, wrapping, or not
    mc::Options o;
    o.hash_bits = bits;
    EXPECT_TRUE(bit_identical(full, mc::extract(torus, 0.0f, dev(), o))) << bits << " bits";
  }
}

TEST(Extract, IntegerVolumeWithIsovalueOnVoxelValues) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> u(0, 4);
  std::vector<float> vals(21 * 22 * 23);
  for (auto& x : vals) x = float(u(rng));
  for (float iso : {0.0f, 1.0f, 2.0f, 4.0f}) {
    std::size_t i = 0;
    auto v = test::sampled([&](double, double, double) { return vals[i++]; }, {21, 22, 23});
    mc::Options o = keys();
    o.cap = true;
    Mesh m = mc::extract(v, iso, dev(), o);
    expect_same_mesh(m, mc::extract_reference(v, iso, o));
    const mc::MeshCheck c = mc::check_mesh(m);
    EXPECT_EQ(c.duplicate_vertices, 0u) << iso;
    EXPECT_EQ(c.degenerate_triangles, 0u) << iso;
    EXPECT_TRUE(c.watertight()) << iso;
    EXPECT_TRUE(c.oriented()) << iso;
    if (iso == 4.0f) {
      EXPECT_EQ(c.triangles, 0u);  // nothing is above the maximum
    }
  }
}

TEST(Extract, IsovalueOutsideTheRangeGivesAnEmptyMesh) {
  auto v = test::ball(20, 6, 10);
  EXPECT_EQ(mc::extract(v, 100.0f, dev()).triangles.size(), 0u);
  EXPECT_EQ(mc::extract(v, -100.0f, dev()).triangles.size(), 0u);
}

TEST(Extract, NanVoxelsCountAsOutside) {
  // Build grids directly (the loader would replace NaN): all NaN gives nothing ...
  volume::Volume v;
  v.grid = openvdb::FloatGrid::create(std::numeric_limits<float>::quiet_NaN());
  v.domain = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15));
  v.grid->denseFill(v.domain, std::numeric_limits<float>::quiet_NaN());
  v.stats.min = 0;
  v.stats.max = 1;
  mc::Options cap;
  cap.cap = true;
  EXPECT_EQ(mc::extract(v, 0.5f, dev(), cap).triangles.size(), 0u);
  // ... and a ball with a NaN slab through it is cut there into two closed pieces.
  auto b = test::ball(30, 11, 14.5);
  auto acc = b.grid->getAccessor();
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x) acc.setValue(openvdb::Coord(x, y, 14), std::numeric_limits<float>::quiet_NaN());
  Mesh m = mc::extract(b, 0.0f, dev(), keys());
  expect_same_mesh(m, mc::extract_reference(b, 0.0f, keys()));
  expect_closed(m, 4);
}

TEST(Extract, OneVoxelThickVolume) {
  auto v = test::sampled([](double x, double y, double) { return float(6 - std::hypot(x - 8, y - 8)); }, {17, 17, 1});
  EXPECT_EQ(mc::extract(v, 0.0f, dev()).triangles.size(), 0u);  // no cells at all
  mc::Options o = keys();
  o.cap = true;
  Mesh m = mc::extract(v, 0.0f, dev(), o);
  expect_same_mesh(m, mc::extract_reference(v, 0.0f, o));
  expect_closed(m, 2);
}

TEST(Extract, PositionsHonourSpacingAndOrigin) {
  auto f = [](double x, double y, double z) { return float(1 - std::sqrt(x * x + y * y + z * z)); };
  const std::array<double, 3> sp{0.05, 0.08, 0.11}, org{-1.3, -1.25, -1.32};
  auto v = test::sampled(f, {53, 33, 25}, sp, org);
  Mesh m = mc::extract(v, 0.0f, dev(), keys());
  expect_same_mesh(m, mc::extract_reference(v, 0.0f, keys()));
  expect_closed(m, 2);
  for (const Vec3f& p : m.positions) {
    const double r = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    ASSERT_NEAR(r, 1.0, 0.02);  // on the unit sphere up to interpolation error
  }
}

TEST(Extract, RunsAreBitIdentical) {
  auto g = test::sampled([](double x, double y, double z) {
    return float(std::sin(0.3 * x) * std::cos(0.3 * y) + std::sin(0.3 * y) * std::cos(0.3 * z) + std::sin(0.3 * z) * std::cos(0.3 * x));
  }, {64, 64, 64});
  EXPECT_TRUE(bit_identical(mc::extract(g, 0.0f, dev()), mc::extract(g, 0.0f, dev())));
}

TEST(Extract, MesherReusesItsIndexAcrossIsovalues) {
  auto v = test::ball(30, 12, 14.5);
  mc::Mesher mesher(v, dev());
  for (float iso : {-2.0f, 0.0f, 3.0f}) {
    mc::ExtractTimings t;
    Mesh m = mesher.extract(iso, {}, &t);
    EXPECT_TRUE(bit_identical(m, mc::extract(v, iso, dev())));
    EXPECT_GT(t.bricks, 0u);
    expect_closed(m, 2);
  }
}

// A .vdb holding two small level-set balls 1e5 voxels apart along every axis (legal: a sparse
// grid's box may be huge; a brick index dense over it would need 12500^3 blocks): the mesh is
// the two balls' meshes, each extracted from a .vdb of its own, vertex for vertex and triangle
// for triangle, and the index follows the leaves.
TEST(Extract, FarApartObjectsInOneSparseVdb) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("isocurv_far_apart_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  auto ball = [](double c) {
    return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
        4.5f, openvdb::Vec3f(float(c + 0.3), float(c - 0.2), float(c + 0.1)), 1.0f);
  };
  auto write = [&](const std::string& name, openvdb::FloatGrid::Ptr g) {
    const std::string path = (dir / name).string();
    openvdb::io::File(path).write({g});
    return volume::load(path);
  };
  openvdb::FloatGrid::Ptr both = ball(0);
  both->tree().merge(ball(1e5)->tree());
  const volume::Volume v = write("both.vdb", both), a = write("a.vdb", ball(0)), b = write("b.vdb", ball(1e5));
  std::filesystem::remove_all(dir);
  ASSERT_FALSE(v.dense);
  ASSERT_GE(v.domain.dim().x(), 100000);
  const mc::BrickIndex index(v);
  EXPECT_TRUE(index.sparse());
  EXPECT_LE(index.blocks(), 27 * v.grid->tree().leafCount());

  const Mesh m = mc::extract(v, 0.0f, dev());
  expect_closed(m, 4);  // two spheres
  Mesh parts = mc::extract(a, 0.0f, dev());
  const Mesh mb = mc::extract(b, 0.0f, dev());
  const auto offset = std::uint32_t(parts.positions.size());
  parts.positions.insert(parts.positions.end(), mb.positions.begin(), mb.positions.end());
  for (const Tri& t : mb.triangles) parts.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  ASSERT_EQ(parts.positions.size(), m.positions.size());
  ASSERT_EQ(parts.triangles.size(), m.triangles.size());
  std::map<Vec3f, std::uint32_t> at;
  for (std::uint32_t i = 0; i < m.positions.size(); ++i) at[m.positions[i]] = i;
  std::vector<std::uint32_t> map(parts.positions.size());
  for (std::size_t i = 0; i < parts.positions.size(); ++i) {
    const auto it = at.find(parts.positions[i]);
    ASSERT_TRUE(it != at.end()) << "vertex " << i << " of the parts is not in the whole";
    map[i] = it->second;
  }
  test::expect_same_triangles(parts, m, map);
}
