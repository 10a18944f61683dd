// A sparse .vdb whose active box holds more than 2^28 voxels: volume::DenseField keeps only its
// 8^3 leaves (the tiled layout), and the ray caster reads it through them, kernel and reference
// alike, seeing what the dense field of the same surface sees.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cmath>
#include <random>

#include "core/cl_device.h"
#include "core/error.h"
#include "screen/ray_cast.h"
#include "volume/dense_field.h"

namespace isocurv::test {
namespace {

/// A level-set ball of radius 20 voxels at (30, 40, 50) and, when `far` > 0, one active
/// background voxel at (far, far, far): a box of about far^3 voxels with 1% of them stored.
volume::Volume ball(int far) {
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      20.0f, openvdb::Vec3f(30, 40, 50), 1.0f, 3.0f);
  if (far > 0) grid->tree().setValueOn(openvdb::Coord(far, far, far), grid->background());
  volume::Volume v;
  v.grid = grid;
  v.path = "ball.vdb";
  v.format = "vdb";
  v.dense = false;
  v.domain = grid->evalActiveVoxelBoundingBox();
  v.inside = volume::Inside::Below;  // a level set: negative inside
  return v;
}

TEST(SparseField, LargeSparseBoxesKeepOnlyTheirLeavesAndReadAsTheGrid) {
  const volume::Volume v = ball(1100);
  const openvdb::Coord d = v.domain.dim();
  ASSERT_GT(std::uint64_t(d.x()) * d.y() * d.z(), volume::kMaxFieldSamples);
  const volume::DenseField f(v);
  EXPECT_TRUE(f.sparse);
  EXPECT_LT(f.values.size(), std::size_t(64) << 20) << "the leaves and the tables, not the box";
  // Every sample reads the grid's value (leaf voxels, tiles and the background alike).
  const openvdb::Coord lo = v.domain.min() & ~7;  // the box starts on a leaf corner
  auto acc = v.grid->getConstAccessor();
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> near(0, 80), any(0, f.nx - 1);
  for (int n = 0; n < 20000; ++n) {
    const int i = n % 2 ? near(rng) : any(rng), j = n % 2 ? near(rng) : any(rng) % f.ny,
              k = n % 2 ? near(rng) : any(rng) % f.nz;
    ASSERT_EQ(f.sample(i, j, k), acc.getValue(lo + openvdb::Coord(i, j, k))) << i << " " << j << " " << k;
  }
  // Smoothing needs the dense layout: refused in one message.
  volume::DenseField g(v);
  EXPECT_THROW(g.smooth(1.0), Error);
}

TEST(SparseField, TheCastSeesWhatTheDenseFieldSees) {
  const volume::DenseField dense(ball(0)), sparse(ball(1100));
  ASSERT_FALSE(dense.sparse);
  ASSERT_TRUE(sparse.sparse);
  std::array<double, 6> box;
  ASSERT_TRUE(sparse.surface_bounds(0.0f, box));
  for (int k = 0; k < 3; ++k) {  // the ball's box, the far voxel ignored (no surface there)
    EXPECT_NEAR(box[2 * k], 30 + 10 * k - 20, 9) << k;
    EXPECT_NEAR(box[2 * k + 1], 30 + 10 * k + 20, 9) << k;
  }
  const Camera cam = fit_camera(box, ViewSpec{}, 4.0 / 3.0);
  const auto frame = screen::view_frame(cam, 96, 72);
  Device& device = Device::default_device();
  const screen::GBuffer d = screen::ray_cast(dense, 0.0f, frame, device);
  const screen::GBuffer s = screen::ray_cast(sparse, 0.0f, frame, device);
  const screen::GBuffer r = screen::ray_cast_reference(sparse, 0.0f, frame);
  ASSERT_GT(d.valid_count(), 500u);
  EXPECT_EQ(s.valid, d.valid);
  EXPECT_EQ(r.valid, s.valid);
  double worst = 0, worst_ref = 0;
  for (std::size_t i = 0; i < s.pixels(); ++i) {
    if (!s.valid[i] || !d.valid[i]) continue;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, double(std::abs(s.position[i][c] - d.position[i][c])));
      if (r.valid[i]) worst_ref = std::max(worst_ref, double(std::abs(s.position[i][c] - r.position[i][c])));
    }
  }
  EXPECT_LT(worst, 1e-3) << "voxels";
  EXPECT_LT(worst_ref, 1e-3) << "voxels";
}

TEST(SparseField, BoxesBeyondTheTileTableAreOneError) {
  try {
    const volume::DenseField f(ball(40000));
    FAIL() << "a 40000^3 box was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ball.vdb"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace isocurv::test
