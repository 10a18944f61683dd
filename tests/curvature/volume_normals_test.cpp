// Gradient normals checked against the faces (volume::gradient_normals_for_mesh) on volumes
// where the gradient misleads: a faint plate one voxel thick beside a bright slab.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/cl_device.h"
#include "core/mesh_measures.h"
#include "core/vec3.h"
#include "curvature/estimate.h"
#include "mc/extract.h"
#include "tests/mc/volumes.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {


// A plate of value 128, one voxel thick (z = 8), a one-voxel gap (z = 9), then a slab of 255
// (z = 10..15), both over x, y in [4, 19]; 0 elsewhere. At isovalue 40 the central differences
// on the plate's upper face see the slab across the gap: the gradient points down there.
volume::Volume plate_beside_slab() {
  return sampled(
      [](double x, double y, double z) {
        if (x < 4 || x > 19 || y < 4 || y > 19) return 0.0f;
        if (z == 8) return 128.0f;
        if (z >= 10 && z <= 15) return 255.0f;
        return 0.0f;
      },
      {24, 24, 24});
}

TEST(VolumeNormals, ThinPlateFallsBackToFaceNormals) {
  openvdb::initialize();
  const volume::Volume v = plate_beside_slab();
  const Mesh mesh = mc::extract(v, 40.0f, Device::default_device());
  ASSERT_GT(mesh.triangles.size(), 100u);
  const std::vector<Vec3f> faces = area_weighted_normals(mesh);

  // The plain gradient normals point against the faces on the plate's upper face.
  const std::vector<Vec3f> plain = volume::gradient_normals(v, mesh.positions);
  std::size_t against = 0;
  for (std::size_t i = 0; i < plain.size(); ++i) against += vec3::wide_dot(plain[i], faces[i]) <= 0;
  ASSERT_GT(against, 50u) << "the plate's upper face (16 x 16 vertices) has misleading gradients";

  const volume::MeshNormals checked = volume::gradient_normals_for_mesh(v, mesh);
  ASSERT_EQ(checked.normals.size(), mesh.positions.size());
  EXPECT_GE(checked.fallbacks(), against);
  EXPECT_GT(checked.opposed, 50u);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    ASSERT_GT(vec3::wide_dot(checked.normals[i], faces[i]), 0.0)
        << "vertex " << i << " disagrees with its faces";
    ASSERT_NEAR(vec3::wide_dot(checked.normals[i], checked.normals[i]), 1.0, 1e-5) << "vertex " << i;
  }
  // Elsewhere the gradient is kept: on the slab's upper face (z = 15.84) the normals are the
  // gradient's, exactly +z.
  std::size_t top = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    if (p[2] > 15.5f && p[0] > 6 && p[0] < 17 && p[1] > 6 && p[1] < 17) {
      ++top;
      EXPECT_EQ(checked.normals[i], plain[i]) << "vertex " << i;
    }
  }
  EXPECT_GT(top, 50u);

  // The flat plate's top then has no curvature: with the raw gradient normals its rim, where the
  // normals turn from the face's direction to the opposite one, has |H| of several per voxel.
  curvature::Options o;
  o.vertex_normals = &checked.normals;
  const curvature::CurvatureField f = curvature::estimate(mesh, Device::default_device(), o);
  double worst = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    if (p[2] > 8.5f && p[2] < 9 && p[0] > 5 && p[0] < 18 && p[1] > 5 && p[1] < 18)
      worst = std::max(worst, double(std::fabs(f.H[i])));
  }
  EXPECT_LT(worst, 1e-3) << "plate top interior";
}

TEST(VolumeNormals, CapVerticesTakeTheBoxFacesNormal) {
  // A ball cut by all six faces of its box, capped: the gradient at the caps points along them
  // (the data goes on beyond the box), so the cap vertices take the face's outward normal.
  openvdb::initialize();
  const volume::Volume v = ball(16, 9.5, 7.5);
  mc::Options o;
  o.cap = true;
  const Mesh mesh = mc::extract(v, 0.0f, Device::default_device(), o);
  const volume::MeshNormals plain = volume::gradient_normals_for_mesh(v, mesh);
  const volume::MeshNormals capped = volume::gradient_normals_for_mesh(v, mesh, true);
  EXPECT_EQ(plain.caps, 0u);
  ASSERT_GT(capped.caps, 50u);
  std::size_t checked = 0, off_before = 0;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    for (int k = 0; k < 3; ++k) {
      const bool low = p[k] < -1e-4f, high = p[k] > 15 + 1e-4f;
      if (!low && !high) continue;
      const bool corner = (p[(k + 1) % 3] < -1e-4f || p[(k + 1) % 3] > 15 + 1e-4f) ||
                          (p[(k + 2) % 3] < -1e-4f || p[(k + 2) % 3] > 15 + 1e-4f);
      if (corner) continue;  // beyond two faces: the faces' mean normal
      Vec3f face{0, 0, 0};
      face[k] = low ? -1.0f : 1.0f;
      EXPECT_GT(vec3::wide_dot(capped.normals[i], face), 0.9999) << i;
      off_before += vec3::wide_dot(plain.normals[i], face) < 0.9;
      ++checked;
    }
  }
  EXPECT_GT(checked, 50u);
  EXPECT_GT(off_before, checked / 2);  // the gradient normals were far off the cap's
}

TEST(VolumeNormals, ZeroGradientIsWeak) {
  // Two plates of 255 one voxel thick with a one-voxel gap: in the gap the central differences
  // of the two plates cancel, so the faces facing the gap get no gradient at all.
  openvdb::initialize();
  const volume::Volume v = sampled(
      [](double x, double y, double z) {
        if (x < 4 || x > 19 || y < 4 || y > 19) return 0.0f;
        return (z == 8 || z == 10) ? 255.0f : 0.0f;
      },
      {24, 24, 24});
  const Mesh mesh = mc::extract(v, 127.5f, Device::default_device());
  const volume::MeshNormals checked = volume::gradient_normals_for_mesh(v, mesh);
  EXPECT_GT(checked.weak, 100u) << "both faces of the gap";
  const std::vector<Vec3f> faces = area_weighted_normals(mesh);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    ASSERT_GT(vec3::wide_dot(checked.normals[i], faces[i]), 0.0) << "vertex " << i;
}

TEST(VolumeNormals, SmoothVolumeKeepsEveryGradientNormal) {
  openvdb::initialize();
  const volume::Volume v = ball(32, 10.3, 15.5);
  const Mesh mesh = mc::extract(v, 0.0f, Device::default_device());
  const volume::MeshNormals checked = volume::gradient_normals_for_mesh(v, mesh);
  EXPECT_EQ(checked.fallbacks(), 0u);
  EXPECT_EQ(checked.normals, volume::gradient_normals(v, mesh.positions));
}

}  // namespace
}  // namespace isocurv::test
