// f1 = 10 sin(r)/r seen from above (SEEDS-SPEC 4.4 acceptance (b)): the per-pixel error against
// the analytic H and K falls as the image resolution doubles, and with the volume's gradient
// normals the LOD lowers the K error when the camera is close (the paper's Fig. 15).
#include <gtest/gtest.h>

#include <cstdio>

#include "core/cl_device.h"
#include "screen/ray_cast.h"
#include "tests/screen/scenes.h"

namespace isocurv::test {
namespace {

// The G-buffer of the exact surface: ray-cast points moved onto the analytic surface, with the
// exact normals, so that only the estimator's own discretisation is measured.
screen::GBuffer exact_buffer(const Scene& s, const Camera& cam, int size) {
  screen::GBuffer g =
      screen::ray_cast(*s.cast, float(s.field->isovalue()), screen::view_frame(cam, size, size),
                       Device::default_device());
  for (std::size_t i = 0; i < g.pixels(); ++i) {
    if (!g.valid[i]) continue;
    const auto& p = g.position[i];
    const Eigen::Vector3d q =
        datasets::project_to_surface(*s.field, Eigen::Vector3d(p[0], p[1], p[2]));
    g.position[i] = {float(q.x()), float(q.y()), float(q.z())};
    g.depth[i] = float(g.frame.eye_depth({q.x(), q.y(), q.z()}));
  }
  exact_normals(g, *s.field);
  return g;
}

TEST(ScreenF1, ErrorFallsWithResolution) {
  const Scene& s = scene("f1", 160);
  const Camera cam = ortho_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 9, 40);
  double last_h = 1e300, last_k = 1e300;
  for (int size : {100, 200, 400}) {
    const screen::GBuffer g = exact_buffer(s, cam, size);
    const auto mask = interior(g, 2);
    for (int edges : {2, 3}) {
      screen::ScreenOptions o;
      o.edges = edges;
      const Mse m =
          mse_against_field(g, screen::estimate(g, Device::default_device(), o), *s.field, mask);
      std::printf("f1 from above, %dx%d, %d edges: MSE H %.2e K %.2e (%zu px)\n", size, size, edges,
                  m.H, m.K, m.n);
      if (edges == 3) continue;
      EXPECT_LT(m.H, 0.5 * last_h) << size;
      EXPECT_LT(m.K, 0.5 * last_k) << size;
      last_h = m.H, last_k = m.K;
    }
  }
}

TEST(ScreenF1, LodLowersTheGaussianErrorWhenClose) {
  const Scene& s = scene("f1", 160);
  // Perspective, close above the central bump, looking down at it.
  Camera cam;
  cam.position = {0.5, 0.3, 12};
  cam.focal_point = {0.5, 0.3, 0};
  cam.view_up = {0, 1, 0};
  cam.view_angle_deg = 40;
  const screen::GBuffer g =
      screen::ray_cast(*s.cast, float(s.field->isovalue()), screen::view_frame(cam, 400, 400),
                       Device::default_device());
  const auto mask = interior(g, 10);
  screen::ScreenOptions plain, lod;
  lod.lod = true;
  const screen::ScreenCurvature a = screen::estimate(g, Device::default_device(), plain);
  const screen::ScreenCurvature b = screen::estimate(g, Device::default_device(), lod);
  std::size_t wide = 0;
  for (std::size_t i = 0; i < g.pixels(); ++i) wide += mask[i] && b.step[i] > 1;
  const Mse ma = mse_against_field(g, a, *s.field, mask),
            mb = mse_against_field(g, b, *s.field, mask);
  std::printf(
      "f1 close-up, gradient normals: no LOD MSE H %.2e K %.2e; LOD MSE H %.2e K %.2e "
      "(%zu of %zu px widened)\n",
      ma.H, ma.K, mb.H, mb.K, wide, ma.n);
  EXPECT_GT(wide, ma.n / 10);
  EXPECT_LT(mb.K, ma.K);
}

}  // namespace
}  // namespace isocurv::test
