// sample(): grid size, index-to-world transform (isotropic and anisotropic), voxel values.
#include <gtest/gtest.h>

#include <random>

#include "core/error.h"
#include "datasets/field.h"
#include "datasets/sample.h"

using namespace isocurv;
using namespace isocurv::datasets;
using Eigen::Vector3d;

namespace {

// Every voxel value equals the field at the voxel's world position (checked on a random subset).
void expect_values_match(const Field& f, const volume::Volume& v, const Vector3d& origin, const Vector3d& spacing) {
  std::mt19937 rng(7);
  const auto dim = v.domain.dim();
  auto acc = v.grid->getConstAccessor();
  for (int n = 0; n < 500; ++n) {
    const openvdb::Coord ijk(rng() % dim.x(), rng() % dim.y(), rng() % dim.z());
    const openvdb::Vec3d w = v.grid->transform().indexToWorld(ijk);
    const Vector3d expected_w = origin + Vector3d(ijk.x(), ijk.y(), ijk.z()).cwiseProduct(spacing);
    ASSERT_NEAR((Vector3d(w.x(), w.y(), w.z()) - expected_w).norm(), 0.0, 1e-12) << ijk;
    EXPECT_EQ(acc.getValue(ijk), static_cast<float>(f.value(expected_w))) << f.name() << " " << ijk;
  }
}

}  // namespace

TEST(Sample, IsotropicGridCoversTheBox) {
  auto f = make_field("torus");  // box [-1,1]^2 x [-0.4,0.4]
  const volume::Volume v = sample(*f, 33);
  const double h = 2.0 / 32;
  EXPECT_EQ(v.domain.min(), openvdb::Coord(0, 0, 0));
  EXPECT_EQ(v.domain.dim(), openvdb::Coord(33, 33, 14));  // 0.8 / h = 12.8 -> 13 steps
  EXPECT_NEAR((v.spacing() - openvdb::Vec3d(h)).length(), 0.0, 1e-15);
  EXPECT_NEAR((v.origin() - openvdb::Vec3d(-1, -1, -0.4)).length(), 0.0, 1e-15);
  EXPECT_EQ(v.inside, volume::Inside::Above);
  EXPECT_EQ(v.format, "generated");
  EXPECT_EQ(v.grid->getName(), "density");
  EXPECT_EQ(v.grid->getGridClass(), openvdb::GRID_UNKNOWN);  // r - d is negative outside
  EXPECT_LT(v.stats.min, 0.0);
  EXPECT_NEAR(v.stats.max, 0.25, h);
  expect_values_match(*f, v, Vector3d(-1, -1, -0.4), Vector3d::Constant(h));
}

TEST(Sample, AnisotropicSpacingAndOriginOffset) {
  auto f = make_field("ellipsoid");  // box [-1,1] x [-0.8,0.8] x [-0.6,0.6]
  SampleOptions o;
  o.anisotropy = Vector3d(1.0, 2.0, 0.5);
  o.origin_offset = Vector3d(0.1, -0.2, 0.3);
  const volume::Volume v = sample(*f, 21, o);
  const Vector3d spacing = 0.1 * o.anisotropy, origin = Vector3d(-1, -0.8, -0.6) + o.origin_offset;
  EXPECT_EQ(v.domain.dim(), openvdb::Coord(21, 9, 25));
  const openvdb::Vec3d s = v.spacing(), org = v.origin();
  EXPECT_NEAR((Vector3d(s.x(), s.y(), s.z()) - spacing).norm(), 0.0, 1e-15);
  EXPECT_NEAR((Vector3d(org.x(), org.y(), org.z()) - origin).norm(), 0.0, 1e-15);
  expect_values_match(*f, v, origin, spacing);
}

TEST(Sample, LevelSetAndDensityKinds) {
  const volume::Volume sphere = sample(*make_field("sphere"), 17);
  EXPECT_EQ(sphere.inside, volume::Inside::Below);
  EXPECT_EQ(sphere.grid->getGridClass(), openvdb::GRID_LEVEL_SET);
  EXPECT_EQ(sphere.grid->getName(), "levelset");
  const volume::Volume bucky = sample(*make_field("buckyball"), 17);
  EXPECT_EQ(bucky.inside, volume::Inside::Above);
  EXPECT_EQ(bucky.grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(bucky.grid->getName(), "density");
}

TEST(Sample, EveryVoxelEqualsTheFieldValue) {
  // Also covers the fields' faster row evaluation (values_along_x), which must match value().
  SampleOptions o;
  o.anisotropy = Vector3d(0.7, 1.0, 1.3);
  o.origin_offset = Vector3d(0.01, 0.02, -0.03);
  for (const auto& name : field_names()) {
    auto f = make_field(name);
    const volume::Volume v = sample(*f, 20, o);
    auto acc = v.grid->getConstAccessor();
    int mismatches = 0;
    for (auto it = v.domain.begin(); it; ++it) {
      const openvdb::Vec3d w = v.grid->transform().indexToWorld(*it);
      mismatches += acc.getValue(*it) != static_cast<float>(f->value(Vector3d(w.x(), w.y(), w.z())));
    }
    EXPECT_EQ(mismatches, 0) << name;
  }
}

TEST(Sample, RejectsBadParameters) {
  auto f = make_field("sphere");
  EXPECT_THROW(sample(*f, 1), Error);
  SampleOptions o;
  o.anisotropy = Vector3d(1, 0, 1);
  EXPECT_THROW(sample(*f, 8, o), Error);
}
