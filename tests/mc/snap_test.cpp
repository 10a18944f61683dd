// Vertex snapping (mc/snap_vertices.h) on integer volumes at isovalues that voxels hold exactly:
// no slivers, no more thin triangles than between voxel values, fusion guarantees kept, the device
// equal to the reference, and every vertex within the snap distance of where it was.
#include <gtest/gtest.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "core/cl_device.h"
#include "core/error.h"
#include "mc/extract.h"
#include "mc/extract_reference.h"
#include "mc/mesh_check.h"
#include "mc/triangle_quality.h"
#include "tests/mc/same_mesh.h"
#include "tests/mc/volumes.h"

using namespace isocurv;

namespace {

Device& dev() { return Device::default_device(); }

// The share of triangles with a smallest angle under one degree (unit spacing).
double thin_share(const mc::TriangleQuality& q) { return q.triangles ? double(q.thin) / double(q.triangles) : 0.0; }

void expect_sound(const Mesh& m, const std::string& what) {
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_GT(c.triangles, 0u) << what;
  EXPECT_EQ(c.duplicate_vertices, 0u) << what;
  EXPECT_EQ(c.unreferenced_vertices, 0u) << what;
  EXPECT_EQ(c.degenerate_triangles, 0u) << what;
  EXPECT_EQ(c.boundary_edges, 0u) << what;
  EXPECT_EQ(c.non_manifold_edges, 0u) << what;
  EXPECT_EQ(c.misoriented_edges, 0u) << what;
}

using test::expect_same_mesh;

// A CT-like solid: a ball and a torus with blurred edges, scaled to 0..255, noise of a few grey
// levels, rounded to integers (uint8 values held as floats).
volume::Volume ct_like(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 3);
  return test::sampled(
      [&](double x, double y, double z) {
        const double ball = 9 - std::sqrt((x - 14) * (x - 14) + (y - 15) * (y - 15) + (z - 16) * (z - 16));
        const double torus = test::torus_density(x - 15, y - 14, z - 9, 8, 2.5);
        const double d = std::max(ball, torus);
        const double v = 255 / (1 + std::exp(-d / 0.8)) + noise(rng);
        return float(std::clamp(std::round(v), 0.0, 255.0));
      },
      {30, 31, 32});
}

// Uniform integers 0..4: every voxel value is a tie at some isovalue, and every case occurs.
volume::Volume small_integers(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 4);
  return test::sampled([&](double, double, double) { return float(u(rng)); }, {21, 22, 23});
}

mc::Options capped(float snap, bool keys) {
  mc::Options o;
  o.cap = true;
  o.snap = snap;
  o.keep_edge_keys = keys;
  return o;
}

}  // namespace

TEST(Snap, WithoutSnappingVoxelValuesLeaveSlivers) {
  // The situation snapping exists for: vertices 1/1024 voxel off each voxel equal to the isovalue.
  const volume::Volume v = ct_like(1);
  const mc::TriangleQuality q = mc::triangle_quality(mc::extract(v, 128.0f, dev(), capped(0, false)), 1.0);
  EXPECT_LT(q.min_area, 1e-6);
}

TEST(Snap, IntegerVolumesAtVoxelValuesHaveNoSliversAndStayManifold) {
  // CT-like volumes: the quality targets. Integer noise (a fifth of the voxels tie at each value,
  // every case and many saddles at voxels): fusion guarantees and device = reference; there some
  // voxels keep their vertices (a merge there would not leave a disc), so thin triangles remain.
  struct Case {
    volume::Volume v;
    std::vector<float> isos;
    bool quality;
  };
  std::vector<Case> cases;
  cases.push_back({ct_like(2), {40, 128, 200}, true});
  cases.push_back({ct_like(7), {90, 160}, true});
  cases.push_back({small_integers(11), {0, 1, 2, 3}, false});
  for (const Case& c : cases)
    for (float iso : c.isos) {
      const std::string what = "iso " + std::to_string(iso);
      const Mesh at = mc::extract(c.v, iso, dev(), capped(mc::kDefaultSnap, true));
      expect_sound(at, what);
      expect_same_mesh(at, mc::extract_reference(c.v, iso, capped(mc::kDefaultSnap, true)));
      if (!c.quality) continue;
      const mc::TriangleQuality q = mc::triangle_quality(at, 1.0);
      const mc::TriangleQuality between =
          mc::triangle_quality(mc::extract(c.v, iso + 0.5f, dev(), capped(mc::kDefaultSnap, false)), 1.0);
      EXPECT_GE(q.min_area, 1e-6) << what;
      EXPECT_LE(thin_share(q), thin_share(between)) << what;
    }
}

TEST(Snap, AVoxelThatCannotMergeMovesItsVerticesOutToTheSnapDistance) {
  // A 3^3 block of 80 in a 0 border, its centre at the isovalue 40, the centre's -y neighbour and
  // its (+1, 0, -1) diagonal neighbour 0: the triangles around the centre form a disc whose rim
  // passes one vertex twice, so merging there would leave a non-manifold edge. Its vertices move
  // out along their edges instead: no triangle keeps the 1/1024-voxel nudge's 1e-6 voxel^2.
  auto block = [](double x, double y, double z) {
    const int i = int(x), j = int(y), k = int(z);
    if (i < 1 || i > 3 || j < 1 || j > 3 || k < 1 || k > 3) return 0.0f;
    if (i == 2 && j == 2 && k == 2) return 40.0f;
    if ((i == 2 && j == 1 && k == 2) || (i == 3 && j == 2 && k == 1)) return 0.0f;
    return 80.0f;
  };
  const volume::Volume v = test::sampled(block, {5, 5, 5});
  mc::ExtractTimings t;
  const Mesh plain = mc::extract(v, 40.0f, dev(), capped(0, false));
  EXPECT_LT(mc::triangle_quality(plain, 1.0).min_area, 1e-6);  // the slivers snapping is for
  const Mesh m = mc::extract(v, 40.0f, dev(), capped(mc::kDefaultSnap, true), &t);
  expect_sound(m, "snapped");
  expect_same_mesh(m, mc::extract_reference(v, 40.0f, capped(mc::kDefaultSnap, true)));
  EXPECT_GT(t.pushed, 0u);
  const mc::TriangleQuality q = mc::triangle_quality(m, 1.0);
  EXPECT_GE(q.min_area, 1e-6);
  // The moved vertices lie on their edges at the snap distance from the centre.
  std::size_t at_snap = 0;
  for (const Vec3f& p : m.positions) {
    const double d = std::hypot(p[0] - 2.0, p[1] - 2.0, p[2] - 2.0);
    if (std::fabs(d - mc::kDefaultSnap) < 1e-5) ++at_snap;
    EXPECT_FALSE(d > 1e-6 && d < mc::kDefaultSnap - 1e-5) << "a vertex left inside the snap distance";
  }
  EXPECT_EQ(at_snap, t.pushed);
}

TEST(Snap, VerticesMoveAtMostTheSnapDistance) {
  const volume::Volume v = ct_like(3);
  for (float snap : {0.05f, 0.2f, 0.5f}) {
    const Mesh off = mc::extract(v, 100.0f, dev(), capped(0, true));
    const Mesh on = mc::extract(v, 100.0f, dev(), capped(snap, true));
    expect_sound(on, "snap " + std::to_string(snap));
    EXPECT_LT(on.positions.size(), off.positions.size());  // vertices met and merged
    std::map<std::uint64_t, std::uint32_t> off_of_key;
    for (std::uint32_t i = 0; i < off.edge_keys.size(); ++i) off_of_key[off.edge_keys[i]] = i;
    double worst = 0;
    for (std::uint32_t i = 0; i < on.positions.size(); ++i) {
      const Vec3f& p = on.positions[i];
      const Vec3f& q = off.positions[off_of_key.at(on.edge_keys[i])];
      worst = std::max(worst, double(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2])));
    }
    EXPECT_LE(worst, snap + 1e-5) << snap;
    EXPECT_GT(worst, 0.0) << snap;
  }
}

TEST(Snap, ZeroTurnsItOffAndTheOutputIsDeterministic) {
  const volume::Volume v = ct_like(4);
  const Mesh a = mc::extract(v, 128.0f, dev(), capped(mc::kDefaultSnap, false));
  const Mesh b = mc::extract(v, 128.0f, dev(), capped(mc::kDefaultSnap, false));
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_TRUE(std::equal(a.positions.begin(), a.positions.end(), b.positions.begin()));
  EXPECT_TRUE(std::equal(a.triangles.begin(), a.triangles.end(), b.triangles.begin()));
  mc::ExtractTimings t;
  mc::extract(v, 128.0f, dev(), capped(0, false), &t);
  EXPECT_EQ(t.snapped, 0u);
  mc::extract(v, 128.0f, dev(), capped(mc::kDefaultSnap, false), &t);
  EXPECT_GT(t.snapped, 0u);
  EXPECT_GT(t.merged, 0u);
}

TEST(Snap, DistanceOutsideItsRangeIsRefused) {
  const volume::Volume v = ct_like(5);
  EXPECT_THROW(mc::extract(v, 128.0f, dev(), capped(0.6f, false)), Error);
  EXPECT_THROW(mc::extract(v, 128.0f, dev(), capped(-0.1f, false)), Error);
}

TEST(Snap, NegativeIndexCoordinatesAndHeavySnapping) {
  // A level-set sphere around the origin: half its voxels lie at negative index coordinates. With
  // a large snap distance nearly every vertex takes part; the mesh stays sound, equal to the
  // reference's, and near the sphere.
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(6.3f, openvdb::Vec3f(0.2f, -0.1f, 0.3f), 0.5f);
  volume::Volume v;
  v.grid = grid;
  v.path = "sphere";
  v.inside = volume::Inside::Below;
  v.dense = false;
  v.domain = grid->evalActiveVoxelBoundingBox();
  v.stats.min = -1.5;  // the narrow band's values
  v.stats.max = 1.5;
  ASSERT_LT(v.domain.min().x(), 0);
  for (float snap : {0.1f, 0.3f}) {
    mc::Options o;
    o.snap = snap;
    o.keep_edge_keys = true;
    const Mesh m = mc::extract(v, 0.0f, dev(), o);
    expect_sound(m, "snap " + std::to_string(snap));
    expect_same_mesh(m, mc::extract_reference(v, 0.0f, o));
    for (const Vec3f& p : m.positions) {
      const double r = std::hypot(p[0] - 0.2, p[1] + 0.1, p[2] - 0.3);
      ASSERT_NEAR(r, 6.3, 0.5 * 2 * snap + 0.05) << snap;  // within twice the snap distance
    }
  }
}
