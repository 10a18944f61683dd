// LoadOptions::z_slab: raw and NRRD (raw encoding) files read in part, as the ranks of a
// distributed run read them: the same voxels as the whole read inside the slab (rounded out to
// whole 8-slice blocks), the whole file's domain, the slab's statistics, and LoadOptions::outside
// for non-finite voxels and the background. Formats that cannot seek read everything.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tests/volume/test_files.h"
#include "volume/load.h"

namespace isocurv {
namespace {

constexpr int kX = 20, kY = 17, kZ = 37;

float voxel(int x, int y, int z) { return float(x * 3 + y * 5 + z * 7 % 11) + 0.25f * float(z); }

std::vector<float> voxels() {
  std::vector<float> v(std::size_t(kX) * kY * kZ);
  for (int z = 0; z < kZ; ++z)
    for (int y = 0; y < kY; ++y)
      for (int x = 0; x < kX; ++x) v[(std::size_t(z) * kY + y) * kX + x] = voxel(x, y, z);
  v[(std::size_t(12) * kY + 3) * kX + 4] = std::numeric_limits<float>::quiet_NaN();  // in the slab
  return v;
}

void expect_slab_of(const volume::Volume& whole, const volume::Volume& part, int first, int last) {
  ASSERT_TRUE(part.slab.has_value());
  EXPECT_EQ(part.slab->min().z(), first);
  EXPECT_EQ(part.slab->max().z(), last);
  EXPECT_EQ(part.domain, whole.domain) << "the domain stays the whole file's";
  auto a = whole.grid->getConstAccessor(), b = part.grid->getConstAccessor();
  std::size_t off = 0;
  for (int z = first; z <= last; ++z)
    for (int y = 0; y < kY; ++y)
      for (int x = 0; x < kX; ++x) {
        const openvdb::Coord c(x, y, z);
        if (x == 4 && y == 3 && z == 12) continue;  // the NaN: each read's own outside value
        off += a.getValue(c) != b.getValue(c);
      }
  EXPECT_EQ(off, 0u);
  EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * (last - first + 1)) << "statistics of the slab read";
  EXPECT_EQ(part.stats.nan_count, first <= 12 && 12 <= last ? 1u : 0u) << "the NaN at z = 12";
}

TEST(Slab, RawReadsOnlyTheBlocksAskedFor) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::string path = dir.file("part_20x17x37_float32.raw");
  voltest::write_file(path, v.data(), v.size() * sizeof(float));
  const volume::Volume whole = volume::load(path);
  EXPECT_FALSE(whole.slab.has_value());
  volume::LoadOptions o;
  o.z_slab = {{9, 20}};  // rounded out to the blocks [8, 23]
  const volume::Volume part = volume::load(path, o);
  expect_slab_of(whole, part, 8, 23);
  // Outside the slab: the background, here the slab's own finite minimum...
  EXPECT_EQ(part.grid->getConstAccessor().getValue(openvdb::Coord(0, 0, 30)), float(part.stats.min));
  // ... or the value the caller gives (a rank: the whole volume's), for the NaN voxel too.
  o.outside = -5.0f;
  const volume::Volume given = volume::load(path, o);
  EXPECT_EQ(given.grid->background(), -5.0f);
  EXPECT_EQ(given.grid->getConstAccessor().getValue(openvdb::Coord(4, 3, 12)), -5.0f);
  // The last block is clamped to the file; a slab past the end reads the last block.
  o.z_slab = {{30, 99}};
  const volume::Volume tail = volume::load(path, o);
  expect_slab_of(whole, tail, 24, kZ - 1);
}

TEST(Slab, NrrdWithDetachedRawDataReadsInPart) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  voltest::write_file(dir.file("data.raw"), v.data(), v.size() * sizeof(float));
  const std::string nhdr = dir.file("part.nhdr");
  voltest::write_file(nhdr, "NRRD0004\ntype: float\ndimension: 3\nsizes: 20 17 37\nencoding: raw\nendian: little\n"
                            "spacings: 1 1 2.5\ndata file: data.raw\n\n");
  const volume::Volume whole = volume::load(nhdr);
  volume::LoadOptions o;
  o.z_slab = {{0, 15}};
  expect_slab_of(whole, volume::load(nhdr, o), 0, 15);
}

TEST(Slab, CompressedFilesAreReadWhole) {
  voltest::TempDir dir;
  const std::vector<float> v = voxels();
  const std::vector<std::uint8_t> bytes(reinterpret_cast<const std::uint8_t*>(v.data()),
                                        reinterpret_cast<const std::uint8_t*>(v.data() + v.size()));
  const std::string path = dir.file("part_20x17x37_float32.raw.gz");
  voltest::write_file(path, voltest::gzip_compress(bytes));
  volume::LoadOptions o;
  o.z_slab = {{8, 15}};
  const volume::Volume part = volume::load(path, o);
  EXPECT_FALSE(part.slab.has_value());
  EXPECT_EQ(part.stats.voxels, std::uint64_t(kX) * kY * kZ);
}

}  // namespace
}  // namespace isocurv
