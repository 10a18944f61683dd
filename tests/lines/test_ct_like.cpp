// Lines on a CT-like volume: a ball with blurred edges, quantised to 8 bits
// with noise, through the real pipeline (marching cubes, gradient normals,
// curvature), not a smooth analytic mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "line_surfaces.h"
#include "lines/extract.h"
#include "lines/polylines.h"
#include "lines/visibility.h"
#include "mc/extract.h"
#include "tests/mc/volumes.h"
#include "volume/gradient_normals.h"

namespace isocurv::lines {
namespace {

// A CT-like ball of radius R voxels centred at (c, c, c) in an n^3 uint8-valued volume (edge
// blurred, noise of deviation `sd` levels, seed `seed`), its marching-cubes surface at the half
// level and that surface's curvature with gradient normals: the real pipeline.
struct NoisyBall {
  Mesh mesh;
  curvature::CurvatureField field;
};
NoisyBall noisy_ball(double R, double c, double sd, unsigned seed, int n) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, sd);
  const volume::Volume v = test::sampled(
      [&](double x, double y, double z) {
        const double d = R - std::sqrt((x - c) * (x - c) + (y - c) * (y - c) +
                                       (z - c) * (z - c));
        return float(
            std::clamp(std::round(255 / (1 + std::exp(-d / 0.8)) + noise(rng)),
                       0.0, 255.0));
      },
      {n, n, n});
  Device &dev = Device::default_device();
  NoisyBall b;
  b.mesh = mc::extract(v, 127.5f, dev);
  const volume::MeshNormals normals =
      volume::gradient_normals_for_mesh(v, b.mesh);
  curvature::Options co;
  co.vertex_normals = &normals.normals;
  b.field = curvature::estimate(b.mesh, dev, co);
  return b;
}

TEST(LinesCtLike, BallContourIsItsSilhouetteAndNoiseGivesFewSuggestiveLines) {
  const double R = 12, c = 20; // voxels
  const NoisyBall b = noisy_ball(R, c, 3, 5, 40);
  const Mesh &mesh = b.mesh;
  const curvature::CurvatureField &field = b.field;
  Device &dev = Device::default_device();
  Camera cam;
  cam.ortho = true;
  cam.focal_point = {c, c, c};
  cam.position = {c, c, c + 100};
  const Segments segs = extract(mesh, field, cam, Options{}, dev);
  const Polylines p = join_segments(segs);
  // The contour: near the equator z = c on the circle of radius R (within a
  // voxel: noise moves the surface by a fraction of one), its length 2 pi R
  // within 5%.
  std::size_t near = 0, contours = 0;
  for (const Segment &g : segs) {
    if (g.type != LineType::contour)
      continue;
    ++contours;
    const double r = std::hypot(g.a[0] - c, g.a[1] - c);
    near += std::fabs(g.a[2] - c) <= 1.5 && std::fabs(r - R) <= 1.0;
  }
  ASSERT_GT(contours, 50u);
  EXPECT_GE(double(near), 0.95 * double(contours));
  EXPECT_NEAR(p.length(LineType::contour), 2 * test::kPi * R,
              0.05 * 2 * test::kPi * R);
  // A ball has no suggestive contours: what the noise leaves is short beside
  // the contour.
  EXPECT_LT(p.length(LineType::suggestive), 0.1 * p.length(LineType::contour));
}

// The drawing of a noisy ball: its silhouette is one unbroken line, not dashes. The contour
// comes from smoothed normals and runs a little inside the rim of the noisy facets; the ray
// test from the line alone hid a third of it.
TEST(LinesCtLike, NoisyBallSilhouetteIsDrawnWhole) {
  const double R = 14, c = 22; // voxels
  const NoisyBall b = noisy_ball(R, c, 12, 11, 44);
  const Mesh &mesh = b.mesh;
  const curvature::CurvatureField &field = b.field;
  Device &dev = Device::default_device();
  Camera cam;
  cam.focal_point = {c, c, c};
  cam.position = {c, c, c + 120};
  cam.view_angle_deg = 20;
  Options o;
  o.lines = parse_line_selection("contours");
  const Segments segs = extract(mesh, field, cam, o, dev);
  const VisibilityTester vis(mesh);
  const std::vector<bool> keep = vis.visible_segments(segs, cam);
  // The rim: contour segments on the silhouette circle (the ray test from the midpoint alone
  // kept 68% of its length; Visibility.TheSphereBehindIsHidden checks that what the surface
  // hides stays hidden).
  double rim = 0, rim_kept = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Segment &g = segs[i];
    const double r = std::hypot(g.a[0] - c, g.a[1] - c), len = test::seg_length(g.a, g.b);
    if (std::fabs(g.a[2] - c) <= 1.5 && std::fabs(r - R) <= 1.0) {
      rim += len;
      rim_kept += keep[i] * len;
    }
  }
  ASSERT_GT(rim, 0.8 * 2 * test::kPi * R);
  EXPECT_GE(rim_kept, 0.97 * rim);
}

} // namespace
} // namespace isocurv::lines
