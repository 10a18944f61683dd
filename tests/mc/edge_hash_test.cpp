// The edge hash (mc/edge_key.h, mirrored in mc/marching_cubes.cl): distinct edges of a volume
// of fewer than 2.8 million 8^3 blocks never collide at 32 bits, neighbouring edges hash close
// together (the sort keeps them together), a block's lower faces are the runs mc_emit searches,
// and a narrowed hash keeps only its low bits.
#include <gtest/gtest.h>

#include <set>
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

TEST(EdgeHash, BlockPointNumbersTheBlocksPoints) {
  std::set<std::uint32_t> seen;
  for (std::uint32_t x = 0; x < 8; ++x)
    for (std::uint32_t y = 0; y < 8; ++y)
      for (std::uint32_t z = 0; z < 8; ++z) {
        const std::uint32_t p = block_point(x, y, z);
        EXPECT_LT(p, 512u);
        EXPECT_TRUE(seen.insert(p).second) << x << " " << y << " " << z;
      }
}

// mc_emit's face_runs: the points at 0 along each axis of d (dx + 2 dy + 4 dz) are exactly these
// runs of block_point numbers.
TEST(EdgeHash, LowerFacesLinesAndCornerAreTheDocumentedRuns) {
  const std::uint32_t runs[8][4] = {{0, 0, 0, 0},     {0, 64, 0, 0},  {56, 120, 0, 0},    {56, 64, 0, 0},
                                    {49, 57, 113, 169}, {49, 57, 0, 0}, {56, 57, 113, 120}, {56, 57, 0, 0}};
  for (int d = 1; d < 8; ++d) {
    std::set<std::uint32_t> on_face, in_runs;
    for (std::uint32_t x = 0; x < 8; ++x)
      for (std::uint32_t y = 0; y < 8; ++y)
        for (std::uint32_t z = 0; z < 8; ++z)
          if ((!(d & 1) || x == 0) && (!(d & 2) || y == 0) && (!(d & 4) || z == 0)) on_face.insert(block_point(x, y, z));
    for (int r = 0; r < 4; r += 2)
      for (std::uint32_t p = runs[d][r]; p < runs[d][r + 1]; ++p) in_runs.insert(p);
    EXPECT_EQ(on_face, in_runs) << "d = " << d;
  }
}
