// The isosurface ray caster: hits on the trilinear isosurface within 1e-4 voxel, the kernel
// against the C++ reference, its normals against volume::gradient_normals, work-group sizes,
// anisotropic voxels, and an isovalue that misses the volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/cl_device.h"
#include "screen/ray_cast.h"
#include "tests/mc/volumes.h"
#include "tests/screen/scenes.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {

// Distance (voxels) of each valid hit from the trilinear isosurface: |s| / |grad s| (index space).
double worst_offset(const volume::DenseField& v, float iso, const screen::GBuffer& g) {
  double worst = 0;
  for (std::size_t i = 0; i < g.pixels(); ++i) {
    if (!g.valid[i]) continue;
    const auto& p = g.position[i];
    const auto q = v.index({p[0], p[1], p[2]});
    std::array<double, 3> grad;
    const double s = v.field(q, iso, &grad);
    const double len = std::sqrt(grad[0] * grad[0] + grad[1] * grad[1] + grad[2] * grad[2]);
    worst = std::max(worst, std::abs(s) / len);
  }
  return worst;
}

Camera iso_camera(const volume::DenseField& v, int w, int h) {
  return fit_camera(v.bounds, ViewSpec{}, double(w) / h);
}

TEST(ScreenRayCast, HitsLieOnTheIsosurface) {
  for (const char* name : {"torus", "gyroid"}) {
    const Scene& s = scene(name, 96);
    const float iso = float(s.field->isovalue());
    const auto frame = screen::view_frame(iso_camera(*s.cast, 200, 150), 200, 150);
    const screen::GBuffer ref = screen::ray_cast_reference(*s.cast, iso, frame);
    const screen::GBuffer dev = screen::ray_cast(*s.cast, iso, frame, Device::default_device());
    const double wr = worst_offset(*s.cast, iso, ref), wd = worst_offset(*s.cast, iso, dev);
    std::printf(
        "%s: %zu hits; worst distance from the trilinear isosurface: reference %.1e, "
        "kernel %.1e voxel\n",
        name, ref.valid_count(), wr, wd);
    EXPECT_GT(ref.valid_count(), 3000u);
    EXPECT_LE(wr, 1e-4);
    EXPECT_LE(wd, 1e-4);
  }
}

TEST(ScreenRayCast, KernelMatchesReference) {
  const Scene& s = scene("torus", 96);
  const float iso = float(s.field->isovalue());
  const auto frame = screen::view_frame(iso_camera(*s.cast, 240, 180), 240, 180);
  const screen::GBuffer ref = screen::ray_cast_reference(*s.cast, iso, frame);
  const screen::GBuffer dev = screen::ray_cast(*s.cast, iso, frame, Device::default_device());
  const double h = s.volume.spacing()[0];
  std::size_t differ = 0, both = 0;
  double worst_p = 0, worst_n = 0;
  for (std::size_t i = 0; i < ref.pixels(); ++i) {
    if (ref.valid[i] != dev.valid[i]) {
      ++differ;
      continue;
    }
    if (!ref.valid[i]) continue;
    double dp = 0, dn = 0;
    for (int k = 0; k < 3; ++k) {
      dp = std::max(dp, double(std::abs(ref.position[i][k] - dev.position[i][k])));
      dn = std::max(dn, double(std::abs(ref.normal[i][k] - dev.normal[i][k])));
    }
    if (dp > 0.01 * h) {  // a grazing ray whose float march found another crossing
      ++differ;
      continue;
    }
    worst_p = std::max(worst_p, dp / h), worst_n = std::max(worst_n, dn);
    EXPECT_NEAR(ref.depth[i], dev.depth[i], 1e-3 * h);
    ++both;
  }
  std::printf(
      "ray cast kernel vs reference: %zu pixels agree (positions within %.1e voxel, "
      "normals %.1e), %zu differ\n",
      both, worst_p, worst_n, differ);
  EXPECT_LE(differ, ref.pixels() / 1000);
  EXPECT_LE(worst_p, 1e-3);
  EXPECT_LE(worst_n, 1e-4);
  EXPECT_EQ(ref.near, dev.near);
  EXPECT_EQ(ref.far, dev.far);
}

TEST(ScreenRayCast, NormalsAreTheVolumesGradientNormals) {
  const Scene& s = scene("ellipsoid", 80);
  const float iso = float(s.field->isovalue());
  const auto frame = screen::view_frame(iso_camera(*s.cast, 120, 90), 120, 90);
  const screen::GBuffer g = screen::ray_cast_reference(*s.cast, iso, frame);
  Positions pts;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < g.pixels(); ++i)
    if (g.valid[i]) pts.push_back(g.position[i]), at.push_back(i);
  ASSERT_GT(pts.size(), 1000u);
  const std::vector<Vec3f> n = volume::gradient_normals(s.volume, pts);
  double worst = 0;
  for (std::size_t j = 0; j < pts.size(); ++j)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, double(std::abs(n[j][k] - g.normal[at[j]][k])));
  EXPECT_LE(worst, 1e-5);
}

// The safe stride skips only stretches where the field cannot reach the isovalue, and the
// secant ends on the same crossing: the plain march (0.5-voxel steps, 16 bisections, midpoint)
// and the default find the same pixels, their hits within 1e-3 voxel of each other (a hit's
// distance from the surface is under 1e-4 voxel, HitsLieOnTheIsosurface; along a grazing ray
// the two hits may lie further apart), in the reference and the kernel. After a jump the 0.5-
// voxel samples fall at other places, so a grazing ray that dips in and out within one step can
// be caught by one march and not the other: at most 1 pixel in 1000 may differ.
TEST(ScreenRayCast, SafeStrideFindsThePlainMarchsHits) {
  for (const char* name : {"gyroid", "torus"}) {
    const Scene& s = scene(name, 96);
    const float iso = float(s.field->isovalue());
    const auto frame = screen::view_frame(iso_camera(*s.cast, 160, 120), 160, 120);
    screen::CastOptions plain;
    plain.safe_stride = false, plain.secant = false, plain.bisections = 16;
    Device& dev = Device::default_device();
    const double h = s.volume.spacing()[0];
    for (bool kernel : {false, true}) {
      const screen::GBuffer a = kernel ? screen::ray_cast(*s.cast, iso, frame, dev, plain)
                                       : screen::ray_cast_reference(*s.cast, iso, frame, plain);
      const screen::GBuffer b = kernel ? screen::ray_cast(*s.cast, iso, frame, dev)
                                       : screen::ray_cast_reference(*s.cast, iso, frame);
      std::size_t differ = 0;
      double worst = 0;
      for (std::size_t i = 0; i < a.pixels(); ++i) {
        if (a.valid[i] != b.valid[i]) {
          ++differ;
          continue;
        }
        if (!a.valid[i]) continue;
        for (int k = 0; k < 3; ++k)
          worst = std::max(worst, double(std::abs(a.position[i][k] - b.position[i][k])) / h);
      }
      std::printf("%s %s: safe stride vs plain march, %zu hits, %zu differ, worst %.1e voxel\n",
                  name, kernel ? "kernel" : "reference", a.valid_count(), differ, worst);
      EXPECT_GT(a.valid_count(), 2000u);
      EXPECT_LE(differ, a.pixels() / 1000);
      EXPECT_LE(worst, 1e-3);
    }
  }
}

TEST(ScreenRayCast, WorkGroupSizesGiveIdenticalBuffers) {
  const Scene& s = scene("torus", 96);
  const float iso = float(s.field->isovalue());
  const auto frame = screen::view_frame(iso_camera(*s.cast, 130, 70), 130, 70);
  const screen::GBuffer a = screen::ray_cast(*s.cast, iso, frame, Device::default_device(), {}, 1);
  for (int wg : {7, 64, 128}) {
    const screen::GBuffer b =
        screen::ray_cast(*s.cast, iso, frame, Device::default_device(), {}, wg);
    EXPECT_EQ(a.valid, b.valid) << wg;
    EXPECT_TRUE(a.position == b.position) << wg;
    EXPECT_TRUE(a.normal == b.normal) << wg;
    EXPECT_EQ(a.depth, b.depth) << wg;
  }
}

TEST(ScreenRayCast, AnisotropicVoxelsFollowTheTransform) {
  const auto field = datasets::make_field("sphere");
  datasets::SampleOptions so;
  so.anisotropy = Eigen::Vector3d(1, 1, 1.7);
  const volume::Volume v = datasets::sample(*field, 96, so);
  const volume::DenseField cv(v);
  const auto frame = screen::view_frame(fit_camera(cv.bounds, ViewSpec{}, 1), 100, 100);
  const screen::GBuffer g = screen::ray_cast(cv, 0.0f, frame, Device::default_device());
  ASSERT_GT(g.valid_count(), 1000u);
  double worst = 0;
  for (std::size_t i = 0; i < g.pixels(); ++i)
    if (g.valid[i]) {
      const auto& p = g.position[i];
      worst = std::max(worst, std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 0.8));
    }
  // The trilinear sphere lies within a small fraction of the longest voxel of the exact one.
  EXPECT_LE(worst, 0.05 * v.spacing()[2]);
}

TEST(ScreenRayCast, AnIsovalueThatMissesGivesAnEmptyBuffer) {
  const Scene& s = scene("torus", 48);
  const auto frame = screen::view_frame(iso_camera(*s.cast, 64, 48), 64, 48);
  std::array<double, 6> box;
  EXPECT_FALSE(s.cast->surface_bounds(1e6f, box));
  EXPECT_EQ(screen::ray_cast(*s.cast, 1e6f, frame, Device::default_device()).valid_count(), 0u);
  EXPECT_EQ(screen::ray_cast_reference(*s.cast, -1e6f, frame).valid_count(), 0u);
  EXPECT_TRUE(s.cast->surface_bounds(float(s.field->isovalue()), box));
}

TEST(ScreenRayCast, SurfaceBoundsLeaveOutSpecksButNotComparablePieces) {
  // A ball of radius 40 (about 300 bricks of surface) with a speck (radius 0.8, one brick) far
  // away: the speck is drawn but not framed. A second ball of radius 6 there instead is framed.
  auto ball = [](double x, double y, double z, double c, double r) {
    return r - std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
  };
  for (double far_radius : {0.8, 6.0}) {
    const volume::Volume v = test::sampled(
        [&](double x, double y, double z) {
          const double far = far_radius < 1 ? 116 : 112;  // the speck inside one brick
          return float(std::max(ball(x, y, z, 48, 40), ball(x, y, z, far, far_radius)));
        },
        {128, 128, 128});
    const volume::DenseField c(v);
    std::array<double, 6> box;
    ASSERT_TRUE(c.surface_bounds(0.0f, box));
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(box[2 * k], 8.0) << k;  // within a brick of the big ball
      if (far_radius < 1)
        EXPECT_LE(box[2 * k + 1], 96.0) << k;
      else
        EXPECT_GE(box[2 * k + 1], 112.0) << k;
    }
  }
}

TEST(ScreenRayCast, TheClipBoxHoldsEveryStraddlingBrickSpecksIncluded) {
  // A ball of radius 40 and a speck (radius 0.8) at (116, 116, 116): the rays are clipped to the
  // straddling bricks' box, which must keep the speck (surface_bounds, for framing, leaves it out)
  // so that a camera on the speck still sees it, kernel and reference alike.
  const volume::Volume v = test::sampled(
      [](double x, double y, double z) {
        auto ball = [&](double c, double r) {
          return r - std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
        };
        return float(std::max(ball(48, 40), ball(116, 0.8)));
      },
      {128, 128, 128});
  const volume::DenseField c(v);
  std::array<int, 6> box{};
  ASSERT_TRUE(c.straddling_box(0.0f, box));
  for (int k = 0; k < 3; ++k) {
    EXPECT_LE(box[2 * k], 8) << k;
    EXPECT_GE(box[2 * k + 1], 117) << k;
    EXPECT_LE(box[2 * k + 1], 127) << k;
  }
  EXPECT_FALSE(c.straddling_box(50.0f, box)) << "no sample above 40: no surface";
  const Camera cam = fit_camera({115.2, 116.8, 115.2, 116.8, 115.2, 116.8}, ViewSpec{}, 1.0);
  const auto frame = screen::view_frame(cam, 32, 32);
  const screen::GBuffer k = screen::ray_cast(c, 0.0f, frame, Device::default_device());
  const screen::GBuffer r = screen::ray_cast_reference(c, 0.0f, frame);
  EXPECT_GT(r.valid_count(), 100u) << "the speck is hit";
  EXPECT_EQ(k.valid, r.valid);
}

TEST(ScreenRayCast, BadSizesAndStepsAreRefused) {
  EXPECT_THROW(screen::view_frame(Camera{}, 0, 10), Error);
  EXPECT_THROW(screen::view_frame(Camera{}, 10, screen::kMaxImageSide + 1), Error);
  const Scene& s = scene("torus", 48);
  screen::CastOptions o;
  o.step = 0.75;
  EXPECT_THROW(screen::ray_cast_reference(*s.cast, 0, screen::view_frame(Camera{}, 8, 8), o),
               Error);
}

}  // namespace
}  // namespace isocurv::test
