// from_dense and compute_stats: grid contents, domain, NaN/Inf replacement, statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "volume/from_dense.h"

using namespace isocurv;
using namespace isocurv::volume;

namespace {

std::vector<float> ramp_values(const std::array<int, 3>& d) {
  std::vector<float> v(std::size_t(d[0]) * d[1] * d[2]);
  for (int z = 0; z < d[2]; ++z)
    for (int y = 0; y < d[1]; ++y)
      for (int x = 0; x < d[0]; ++x) v[(std::size_t(z) * d[1] + y) * d[0] + x] = float(x + 10 * y + 100 * z);
  return v;
}

}  // namespace

TEST(VolumeFromDense, CopiesValuesXFastest) {
  const std::array<int, 3> d{5, 4, 3};
  const auto data = ramp_values(d);
  auto xf = openvdb::math::Transform::createLinearTransform(0.5);
  Volume v = from_dense(data.data(), d, xf, {"mem", "generated", "float", "ramp", Inside::Above});
  EXPECT_EQ(v.domain, openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(4, 3, 2)));
  EXPECT_TRUE(v.dense);
  auto acc = v.grid->getConstAccessor();
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 5; ++x) EXPECT_EQ(acc.getValue(openvdb::Coord(x, y, z)), float(x + 10 * y + 100 * z));
  EXPECT_EQ(v.grid->background(), 0.0f);
  EXPECT_EQ(v.stats.min, 0.0);
  EXPECT_EQ(v.stats.max, 234.0);
  EXPECT_EQ(v.stats.voxels, 60u);
  EXPECT_NEAR(v.stats.mean, (2.0 + 15.0 + 100.0), 1e-9);
  ASSERT_EQ(v.stats.histogram.size(), 256u);
  std::uint64_t total = 0;
  for (auto c : v.stats.histogram) total += c;
  EXPECT_EQ(total, 60u);
  EXPECT_EQ(v.stats.histogram.front(), 1u);
  EXPECT_EQ(v.stats.histogram.back(), 1u);
  EXPECT_DOUBLE_EQ(v.spacing().x(), 0.5);
  EXPECT_EQ(v.grid->getName(), "ramp");
}

TEST(VolumeFromDense, NonFiniteCountedAndReplacedByOutsideValue) {
  const std::array<int, 3> d{4, 4, 4};
  std::vector<float> data(64, 5.0f);
  data[1] = 2.0f;
  data[2] = 9.0f;
  data[10] = std::numeric_limits<float>::quiet_NaN();
  data[11] = std::numeric_limits<float>::quiet_NaN();
  data[20] = std::numeric_limits<float>::infinity();
  data[21] = -std::numeric_limits<float>::infinity();
  data[22] = std::numeric_limits<float>::infinity();
  for (Inside side : {Inside::Above, Inside::Below}) {
    Volume v = from_dense(data.data(), d, nullptr, {"nan.raw", "raw", "float", "", side});
    const float outside = side == Inside::Above ? 2.0f : 9.0f;
    EXPECT_EQ(v.stats.nan_count, 2u);
    EXPECT_EQ(v.stats.inf_count, 3u);
    EXPECT_EQ(v.stats.voxels, 64u);
    EXPECT_EQ(v.stats.min, 2.0);
    EXPECT_EQ(v.stats.max, 9.0);
    EXPECT_EQ(v.grid->background(), outside);
    auto acc = v.grid->getConstAccessor();
    EXPECT_EQ(acc.getValue(openvdb::Coord(2, 2, 0)), outside);  // index 10
    EXPECT_EQ(acc.getValue(openvdb::Coord(0, 1, 1)), outside);  // index 20
    EXPECT_EQ(acc.getValue(openvdb::Coord(1, 0, 0)), 2.0f);
    EXPECT_EQ(acc.getValue(openvdb::Coord(3, 3, 3)), 5.0f);
    EXPECT_EQ(v.inside, side);
  }
}

TEST(VolumeFromDense, AllNonFiniteIsAnError) {
  std::vector<float> data(8, std::numeric_limits<float>::quiet_NaN());
  data[3] = std::numeric_limits<float>::infinity();
  try {
    from_dense(data.data(), {2, 2, 2}, nullptr, {"allnan.raw", "raw", "float", "", Inside::Above});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("allnan.raw"), std::string::npos);
  }
}

TEST(VolumeFromDense, BadDimensionsAreAnError) {
  float one = 1;
  EXPECT_THROW(from_dense(&one, {1, 0, 1}, nullptr, {"zero", "raw", "float", "", Inside::Above}), Error);
  EXPECT_THROW(from_dense(&one, {1, -3, 1}, nullptr, {"neg", "raw", "float", "", Inside::Above}), Error);
}

TEST(VolumeFromDense, ConstantVolumeIsWellDefined) {
  std::vector<float> data(27, 3.0f);
  Volume v = from_dense(data.data(), {3, 3, 3}, nullptr, {"const", "raw", "float", "", Inside::Above});
  EXPECT_EQ(v.stats.min, 3.0);
  EXPECT_EQ(v.stats.max, 3.0);
  EXPECT_EQ(v.stats.mean, 3.0);
  EXPECT_EQ(v.stats.suggested_isovalue, 3.0);
  EXPECT_EQ(v.grid->tree().getValue(openvdb::Coord(1, 1, 1)), 3.0f);
}

TEST(VolumeFromDense, BinaryVolumeSuggestsMidpoint) {
  // A 0/255 ball: the suggested isovalue is the midpoint of the labels.
  const std::array<int, 3> d{32, 32, 32};
  std::vector<float> data(32 * 32 * 32);
  for (int z = 0; z < 32; ++z)
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        data[(z * 32 + y) * 32 + x] = ((x - 16) * (x - 16) + (y - 16) * (y - 16) + (z - 16) * (z - 16) < 100) ? 255.f : 0.f;
  Volume v = from_dense(data.data(), d, nullptr, {"ball", "generated", "uint8", "", Inside::Above});
  EXPECT_NEAR(v.stats.suggested_isovalue, 127.5, 1e-9);
  // Stats from the sparse grid (background tiles) must equal a brute-force count.
  std::uint64_t above = 0;
  for (float f : data) above += f > 0;
  EXPECT_EQ(v.stats.histogram.back(), above);
  EXPECT_EQ(v.stats.histogram.front(), data.size() - above);
}

TEST(VolumeComputeStats, SparseCountsActiveVoxelsOnly) {
  auto grid = openvdb::FloatGrid::create(3.0f);
  grid->tree().setValue(openvdb::Coord(0, 0, 0), -1.0f);
  grid->tree().setValue(openvdb::Coord(100, 0, 0), 1.0f);
  grid->tree().setValueOff(openvdb::Coord(50, 0, 0), 7.0f);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  Volume v;
  v.grid = grid;
  v.dense = false;
  v.grid_class = "level set";
  v.domain = grid->evalActiveVoxelBoundingBox();
  compute_stats(v);
  EXPECT_EQ(v.stats.voxels, 2u);
  EXPECT_EQ(v.stats.min, -1.0);
  EXPECT_EQ(v.stats.max, 1.0);
  EXPECT_EQ(v.stats.mean, 0.0);
  EXPECT_EQ(v.stats.suggested_isovalue, 0.0);
}

TEST(VolumeComputeStats, DenseDomainCountsTilesAndBackground) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 2.0f, true);  // tiles of 8^3
  Volume v;
  v.grid = grid;
  v.dense = true;
  v.domain = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(19, 15, 15));
  compute_stats(v);
  EXPECT_EQ(v.stats.voxels, 20u * 16 * 16);
  EXPECT_EQ(v.stats.histogram.back(), 16u * 16 * 16);
  EXPECT_EQ(v.stats.histogram.front(), 4u * 16 * 16);
}
