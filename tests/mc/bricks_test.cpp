// mc::BrickIndex: the candidates are the bricks whose samples (with their apron) straddle the
// isovalue, found by brute force over every brick of the frame, plus only those next to a NaN,
// for a lone inside voxel in each part of a block a lower brick's apron reads (corner, lines,
// faces, interior); the gather keeps exactly the straddling ones, with the frame's signed values.
#include "tests/test_paths.h"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>
#include <tuple>
#include <vector>

#include <openvdb/tools/LevelSetSphere.h>

#include "mc/bricks.h"
#include "mc/frame.h"
#include "tests/mc/volumes.h"
#include "volume/from_dense.h"
#include "volume/load.h"

namespace isocurv {
namespace {

using Coords = std::vector<openvdb::Coord>;

// Every brick of the frame whose 9^3 samples hold both an inside (> 0) and an outside value.
Coords straddling(const volume::Volume& v, const mc::Frame& f) {
  Coords out;
  auto acc = v.grid->getConstAccessor();
  auto floor8 = [](int c) { return c >= 0 ? c / 8 * 8 : -((-c + 7) / 8) * 8; };
  const openvdb::Coord lo(floor8(f.cells.min().x()), floor8(f.cells.min().y()), floor8(f.cells.min().z()));
  for (int x = lo.x(); x <= f.cells.max().x(); x += 8)
    for (int y = lo.y(); y <= f.cells.max().y(); y += 8)
      for (int z = lo.z(); z <= f.cells.max().z(); z += 8) {
        bool in = false, outside = false;
        for (int i = 0; i < mc::kApron; ++i)
          for (int j = 0; j < mc::kApron; ++j)
            for (int k = 0; k < mc::kApron; ++k) {
              const openvdb::Coord p(x + i, y + j, z + k);
              const float s = f.signed_value(p, acc.getValue(p));
              in |= s > 0;
              outside |= !(s > 0);
            }
        if (in && outside) out.emplace_back(x, y, z);
      }
  return out;
}

class LoneVoxel : public ::testing::TestWithParam<std::tuple<int, int, int>> {};

TEST_P(LoneVoxel, SelectsAndGathersExactlyTheStraddlingBricks) {
  // Plain ints, not structured bindings: lambdas may capture those only from C++20 (clang).
  const int vx = std::get<0>(GetParam()), vy = std::get<1>(GetParam()), vz = std::get<2>(GetParam());
  // 40^3 at 0 with one voxel at 1 (isovalue 0.5), and a NaN, a +Inf and a -Inf voxel far from it.
  const float inf = std::numeric_limits<float>::infinity();
  auto v = test::sampled([&](double x, double y, double z) {
    if (int(x) == vx && int(y) == vy && int(z) == vz) return 1.0f;
    if (int(x) == 37 && int(y) == 2 && int(z) == 30) return std::numeric_limits<float>::quiet_NaN();
    if (int(x) == 37 && int(y) == 34 && int(z) == 2) return inf;
    if (int(x) == 3 && int(y) == 37 && int(z) == 35) return -inf;
    return 0.0f;
  }, {40, 40, 40});
  const mc::Frame f = mc::make_frame(v, 0.5f, {});
  const mc::BrickIndex index(v);
  Coords origins = index.candidates(f);
  const Coords want = straddling(v, f);
  ASSERT_FALSE(want.empty());
  const std::set<openvdb::Coord> candidates(origins.begin(), origins.end());
  for (const openvdb::Coord& c : want) EXPECT_TRUE(candidates.count(c)) << c;
  // Nearly exact: the only extra candidates are the bricks whose samples include a block holding
  // the NaN or an infinity (such a block counts as possibly outside as a whole).
  const std::set<openvdb::Coord> wanted(want.begin(), want.end());
  const openvdb::CoordBBox nonfinite_blocks[] = {{openvdb::Coord(32, 0, 24), openvdb::Coord(39, 7, 31)},
                                                 {openvdb::Coord(32, 32, 0), openvdb::Coord(39, 39, 7)},
                                                 {openvdb::Coord(0, 32, 32), openvdb::Coord(7, 39, 39)}};
  for (const openvdb::Coord& c : origins) {
    if (!wanted.count(c)) {
      bool near_nonfinite = false;
      for (const auto& block : nonfinite_blocks)
        near_nonfinite |= openvdb::CoordBBox(c, c + openvdb::Coord(8)).hasOverlap(block);
      EXPECT_TRUE(near_nonfinite) << "extra candidate " << c;
    }
  }
  std::vector<float> samples(origins.size() * mc::kBrickSamples);
  index.gather(f, origins, samples.data());
  EXPECT_EQ(origins, want);  // the straddling ones, in the candidates' order (x, y, z; z fastest)
  auto acc = v.grid->getConstAccessor();
  for (std::size_t b = 0; b < origins.size(); ++b)
    for (int x = 0; x < mc::kApron; ++x)
      for (int y = 0; y < mc::kApron; ++y)
        for (int z = 0; z < mc::kApron; ++z) {
          const openvdb::Coord p = origins[b] + openvdb::Coord(x, y, z);
          ASSERT_EQ(samples[b * mc::kBrickSamples + z + 9 * y + 81 * x], f.signed_value(p, acc.getValue(p))) << p;
        }
}

// An infinite voxel reads as outside: in a volume that is inside everywhere else (but past its
// edge), the bricks whose samples hold it straddle, and are selected and kept (its block's range
// alone, up to +Inf, would say "all inside").
TEST(BrickIndex, InfinityAmongInsideValuesIsOutside) {
  for (const float bad : {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()}) {
    auto v = test::sampled([](double, double, double) { return 1.0f; }, {24, 24, 24});
    v.grid->tree().setValue(openvdb::Coord(12, 13, 14), bad);  // loading would have replaced it
    const mc::Frame f = mc::make_frame(v, 0.5f, {});
    const mc::BrickIndex index(v);
    Coords origins = index.candidates(f);
    const Coords want = straddling(v, f);
    ASSERT_TRUE(std::count(want.begin(), want.end(), openvdb::Coord(8, 8, 8)));  // holds the voxel
    std::vector<float> samples(origins.size() * mc::kBrickSamples);
    index.gather(f, origins, samples.data());
    EXPECT_EQ(origins, want) << bad;
  }
}

// The selected bricks and their samples: the candidates, gathered (those that straddle).
struct Selection {
  Coords origins;
  std::vector<float> samples;
};
Selection select(const mc::BrickIndex& index, const mc::Frame& f) {
  Selection s;
  s.origins = index.candidates(f);
  s.samples.resize(s.origins.size() * mc::kBrickSamples);
  index.gather(f, s.origins, s.samples.data());
  s.samples.resize(s.origins.size() * mc::kBrickSamples);
  return s;
}

// A sparse fog grid (background 0) holding every kind of constant region OpenVDB stores: an
// upper-node tile (128^3, value 1), beside it a lower-node tile (8^3) of another value and one
// of the same value, a NaN tile, a leaf, and an inactive root tile (4096^3) that the index's
// box cuts, touched by an active voxel beside it.
volume::Volume tiles_of_every_level() {
  volume::Volume v;
  v.grid = openvdb::FloatGrid::create(0.0f);
  openvdb::FloatTree& t = v.grid->tree();
  v.grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(127)), 1.0f, true);
  v.grid->fill(openvdb::CoordBBox(openvdb::Coord(128, 0, 0), openvdb::Coord(135, 7, 7)), 2.0f, true);
  v.grid->fill(openvdb::CoordBBox(openvdb::Coord(-8, 8, 8), openvdb::Coord(-1, 15, 15)), 1.0f, true);
  v.grid->fill(openvdb::CoordBBox(openvdb::Coord(0, 0, 128), openvdb::Coord(7, 7, 135)),
               std::numeric_limits<float>::quiet_NaN(), true);
  t.setValue(openvdb::Coord(140, 20, 20), 3.0f);
  t.addTile(3, openvdb::Coord(4096, 0, 0), 1.0f, false);
  t.setValue(openvdb::Coord(4095, 3, 3), 1.0f);
  v.dense = false;
  v.domain = v.grid->evalActiveVoxelBoundingBox();
  volume::compute_stats(v);
  return v;
}

// The sparse layout selects and gathers exactly what the dense one does (same bricks, same
// order, same samples), for every kind of tile, a level set with tiles inside, both insides,
// and isovalues between the tiles' values; while holding fewer blocks.
TEST(BrickIndex, SparseLayoutGivesWhatTheDenseOneGives) {
  volume::Volume tiles = tiles_of_every_level();
  volume::Volume ls;
  ls.grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(30.0f, openvdb::Vec3f(0.3f, -0.2f, 0.1f), 0.5f);
  ls.dense = false;
  ls.inside = volume::Inside::Below;
  ls.domain = ls.grid->evalActiveVoxelBoundingBox();
  volume::compute_stats(ls);
  struct Case {
    volume::Volume* v;
    volume::Inside inside;
    float iso;
  };
  const Case cases[] = {{&tiles, volume::Inside::Above, 0.5f}, {&tiles, volume::Inside::Above, 1.5f},
                        {&tiles, volume::Inside::Above, 2.5f}, {&tiles, volume::Inside::Below, 0.5f},
                        {&ls, volume::Inside::Below, 0.0f},    {&ls, volume::Inside::Below, 0.7f},
                        {&ls, volume::Inside::Above, -0.3f}};
  for (const Case& c : cases) {
    c.v->inside = c.inside;
    const mc::BrickIndex dense(*c.v, mc::BrickIndex::Layout::dense);
    const mc::BrickIndex sparse(*c.v, mc::BrickIndex::Layout::sparse);
    ASSERT_FALSE(dense.sparse());
    ASSERT_TRUE(sparse.sparse());
    EXPECT_LT(sparse.blocks(), dense.blocks());
    const mc::Frame f = mc::make_frame(*c.v, c.iso, {});
    const Selection a = select(dense, f), b = select(sparse, f);
    ASSERT_FALSE(a.origins.empty()) << c.iso;
    EXPECT_EQ(a.origins, b.origins) << c.iso;
    EXPECT_TRUE(std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof(float)) == 0 &&
                a.samples.size() == b.samples.size())
        << c.iso;
  }
  // The tile faces are where the surface is: at 0.5 the upper tile's six faces (16 x 16 blocks
  // each) are all selected, in both layouts.
  tiles.inside = volume::Inside::Above;
  const mc::Frame f = mc::make_frame(tiles, 0.5f, {});
  const Selection s = select(mc::BrickIndex(tiles, mc::BrickIndex::Layout::sparse), f);
  EXPECT_TRUE(std::count(s.origins.begin(), s.origins.end(), openvdb::Coord(-8, 64, 64)));
  EXPECT_TRUE(std::count(s.origins.begin(), s.origins.end(), openvdb::Coord(64, 120, 64)));
  EXPECT_TRUE(std::count(s.origins.begin(), s.origins.end(), openvdb::Coord(64, 64, 120)));
  // The root tile's face at x = 4096, inside the index's box: beside the leaf at 4095 and beyond.
  EXPECT_TRUE(std::count(s.origins.begin(), s.origins.end(), openvdb::Coord(4088, 0, 0)));
  EXPECT_TRUE(std::count(s.origins.begin(), s.origins.end(), openvdb::Coord(4088, 48, 64)));
}

// The same on the real sparse .vdb files (a level set, a cube with interior tiles, smoke), at
// their suggested isovalues and near their value ranges' ends.
TEST(BrickIndex, SparseLayoutGivesWhatTheDenseOneGivesOnRealVdbFiles) {
  int found = 0;
  for (const char* file : {"vdb_sphere/sphere.vdb", "vdb_cube/cube.vdb", "vdb_smoke/smoke.vdb"}) {
    const std::string path = std::string(isocurv::test_paths::shared_datasets()) + "/" + file;
    if (!std::filesystem::exists(path)) continue;
    ++found;
    const volume::Volume v = volume::load(path);
    const mc::BrickIndex dense(v, mc::BrickIndex::Layout::dense);
    const mc::BrickIndex sparse(v, mc::BrickIndex::Layout::sparse);
    const double span = v.stats.max - v.stats.min;
    for (const double iso : {v.stats.suggested_isovalue, v.stats.min + 0.05 * span, v.stats.max - 0.05 * span}) {
      const mc::Frame f = mc::make_frame(v, float(iso), {});
      const Selection a = select(dense, f), b = select(sparse, f);
      EXPECT_EQ(a.origins, b.origins) << file << " at " << iso;
      EXPECT_TRUE(a.samples == b.samples) << file << " at " << iso;
    }
  }
  if (found == 0) GTEST_SKIP() << "no .vdb datasets in " << isocurv::test_paths::shared_datasets();
}

// Two small balls 1e5 voxels apart along every axis (a legal sparse .vdb): the automatic layout
// is sparse, holding at most 27 blocks a leaf, where a dense index would need 12500^3 blocks.
TEST(BrickIndex, FarApartObjectsCostTheirLeavesNotTheirBox) {
  volume::Volume v;
  v.grid = openvdb::FloatGrid::create(0.0f);
  for (const int c : {0, 100000})
    for (int x = -6; x <= 6; ++x)
      for (int y = -6; y <= 6; ++y)
        for (int z = -6; z <= 6; ++z)
          v.grid->tree().setValue(openvdb::Coord(c + x, c + y, c + z), float(5 - std::sqrt(double(x * x + y * y + z * z))));
  v.dense = false;
  v.domain = v.grid->evalActiveVoxelBoundingBox();
  volume::compute_stats(v);
  const mc::BrickIndex index(v);
  EXPECT_TRUE(index.sparse());
  EXPECT_LE(index.blocks(), 27 * v.grid->tree().leafCount());
  const Selection s = select(index, mc::make_frame(v, 0.0f, {}));
  EXPECT_EQ(s.origins.size(), 2u * 8u);  // each ball straddles the 8 bricks around its centre
}

// Block corners (read by 8 bricks), points on a block's lower lines and faces (read by 4 and 2),
// an interior point (1), and points at the volume's edge (clipped bricks around them).
INSTANTIATE_TEST_SUITE_P(Mc, LoneVoxel,
                         ::testing::Values(std::make_tuple(8, 8, 8), std::make_tuple(16, 24, 32),
                                           std::make_tuple(8, 8, 13), std::make_tuple(8, 13, 16),
                                           std::make_tuple(13, 16, 24), std::make_tuple(8, 13, 21),
                                           std::make_tuple(10, 11, 12), std::make_tuple(39, 39, 39),
                                           std::make_tuple(0, 0, 0)));

}  // namespace
}  // namespace isocurv
