// mc::BrickIndex: the candidates are the bricks whose samples (with their apron) straddle the
// isovalue, found by brute force over every brick of the frame, plus only those next to a NaN,
// for a lone inside voxel in each part of a block a lower brick's apron reads (corner, lines,
// faces, interior); the gather keeps exactly the straddling ones, with the frame's signed values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <vector>

#include "mc/bricks.h"
#include "mc/frame.h"
#include "tests/mc/volumes.h"

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
  const auto [vx, vy, vz] = GetParam();
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
