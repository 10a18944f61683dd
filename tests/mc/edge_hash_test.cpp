// The edge hash (mc/edge_key.h, mirrored in mc/marching_cubes.cl): distinct edges of a volume
// of fewer than 2.8 million 8^3 blocks never collide at 32 bits, neighbouring edges hash close
// together (the sort keeps them together), and a narrowed hash keeps only its low bits.
#include <gtest/gtest.h>

#include <unordered_set>

#include "mc/edge_key.h"

using namespace isocurv::mc;

TEST(EdgeHash, DistinctEdgesOfAVolumeDoNotCollide) {
  const std::uint32_t nx = 37, ny = 29, nz = 21;  // not multiples of 8
  const std::uint32_t bz = nz / 8 + 1, by = ny / 8 + 1;
  std::unordered_set<std::uint32_t> seen;
  for (std::uint32_t z = 0; z < nz; ++z)
    for (std::uint32_t y = 0; y < ny; ++y)
      for (std::uint32_t x = 0; x < nx; ++x)
        for (std::uint32_t a = 0; a < 3; ++a) EXPECT_TRUE(seen.insert(edge_hash(x, y, z, a, bz, by, 32)).second);
}

TEST(EdgeHash, NeighboursInABlockHashWithinOneBlocksSlots) {
  const std::uint32_t h = edge_hash(16, 8, 24, 0, 10, 10, 32);
  for (std::uint32_t d = 0; d < 8; ++d) {
    const std::uint32_t n = edge_hash(16 + d, 8 + d, 24 + d, 2, 10, 10, 32);
    EXPECT_LT(n - h, 1536u);
  }
}

TEST(EdgeHash, NarrowHashKeepsTheLowBits) {
  for (std::uint32_t x = 0; x < 40; ++x) {
    const std::uint32_t full = edge_hash(x, 3, 5, 1, 6, 6, 32);
    EXPECT_EQ(edge_hash(x, 3, 5, 1, 6, 6, 4), full & 15u);
  }
}
