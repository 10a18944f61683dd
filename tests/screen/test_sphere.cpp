// The sphere (SEEDS-SPEC 4.4 acceptance (a), 4.5): the per-pixel estimator is exact on spheres,
// so with the field's exact normals every pixel 2 px inside the silhouette has H = 1/R and
// K = 1/R^2 to 1e-3 (2 and 3 edges, LOD on and off; the spec allows K 2e-3); with the volume's
// gradient normals H and K within 3%; Mellado's sphere fit within 1% away from the silhouette.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/cl_device.h"
#include "screen/ray_cast.h"
#include "tests/screen/scenes.h"

namespace isocurv::test {
namespace {

constexpr double kR = 0.8;

struct Worst {
  double h = 0, k = 0;
  std::size_t n = 0, missing = 0;
};

Worst worst_error(const screen::ScreenCurvature& c, const std::vector<std::uint8_t>& mask) {
  Worst w;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    if (!c.valid[i]) {
      ++w.missing;
      continue;
    }
    w.h = std::max(w.h, std::abs(c.H[i] - 1 / kR) * kR);
    w.k = std::max(w.k, std::abs(c.K[i] - 1 / (kR * kR)) * kR * kR);
    ++w.n;
  }
  return w;
}

screen::GBuffer sphere_buffer(int size, const Camera& cam) {
  const Scene& s = scene("sphere", 256);
  return screen::ray_cast(*s.cast, float(s.field->isovalue()), screen::view_frame(cam, size, size),
                          Device::default_device());
}

TEST(ScreenSphere, ExactNormalsGiveExactCurvature) {
  // Measured: H 2.83e-4, K 5.67e-4 at most, every variant. That is not the estimator's error but
  // the hit points': they lie on the 256^3 volume's trilinear isosurface, up to 2.4e-5 R off the
  // sphere, and a pixel triangle whose corners sit on different concentric spheres (with exact
  // radial normals) is not exactly a sphere's; the worst pixels are near the silhouette. Moved
  // onto the exact sphere, the same pixels give H 2.2e-5, K 4.5e-5 (float rounding), asserted
  // below 1e-4 (reference and device).
  const Scene& s = scene("sphere", 256);
  screen::GBuffer g = sphere_buffer(1024, ortho_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 0.9));
  exact_normals(g, *s.field);
  const auto mask = interior(g, 2);
  const std::size_t inner = std::count(mask.begin(), mask.end(), 1);
  ASSERT_GT(inner, 500000u);
  screen::GBuffer on_sphere = g;
  for (std::size_t i = 0; i < on_sphere.pixels(); ++i) {
    if (!on_sphere.valid[i]) continue;
    auto& p = on_sphere.position[i];
    const double n = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    for (int k = 0; k < 3; ++k) p[k] = float(p[k] * kR / n);
  }
  exact_normals(on_sphere, *s.field);
  const Worst ref = worst_error(screen::estimate_reference(on_sphere), mask);
  const Worst dev = worst_error(screen::estimate(on_sphere, Device::default_device()), mask);
  std::printf(
      "sphere exact normals, hit points moved onto the sphere: max rel. error reference H %.2e "
      "K %.2e, device H %.2e K %.2e\n",
      ref.h, ref.k, dev.h, dev.k);
  EXPECT_LE(ref.h, 1e-4);
  EXPECT_LE(ref.k, 1e-4);
  EXPECT_LE(dev.h, 1e-4);
  EXPECT_LE(dev.k, 1e-4);
  for (int edges : {2, 3})
    for (bool lod : {false, true}) {
      screen::ScreenOptions o;
      o.edges = edges, o.lod = lod;
      const screen::ScreenCurvature c = screen::estimate(g, Device::default_device(), o);
      const Worst w = worst_error(c, mask);
      std::printf("sphere exact normals, %d edges, LOD %s: max rel. error H %.2e K %.2e (%zu px)\n",
                  edges, lod ? "on" : "off", w.h, w.k, w.n);
      EXPECT_EQ(w.missing, 0u);
      EXPECT_LE(w.h, 1e-3) << edges << " edges, lod " << lod;
      EXPECT_LE(w.k, 1e-3) << edges << " edges, lod " << lod;
    }
}

TEST(ScreenSphere, LodWidensTheTrianglesNearTheCameraAndStaysExact) {
  // A perspective camera close to the sphere: near pixels get steps above 1.
  const Scene& s = scene("sphere", 256);
  Camera cam;
  cam.position = {0, 0, 1.1};
  cam.focal_point = {0, 0, 0};
  cam.view_up = {0, 1, 0};
  cam.view_angle_deg = 60;
  screen::GBuffer g = sphere_buffer(512, cam);
  exact_normals(g, *s.field);
  const auto mask = interior(g, 12);  // beyond the widest step
  for (int fan : {4, 8}) {
    screen::ScreenOptions o;
    o.lod = true, o.fan = fan;
    const screen::ScreenCurvature c = screen::estimate(g, Device::default_device(), o);
    std::size_t wide = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) wide += mask[i] && c.step[i] > 1;
    const Worst w = worst_error(c, mask);
    std::printf(
        "sphere close-up, LOD %d-fan: %zu of %zu px with step > 1, max rel. error H %.2e "
        "K %.2e\n",
        fan, wide, w.n, w.h, w.k);
    EXPECT_GT(wide, w.n / 4);
    EXPECT_LE(w.h, 1e-3);  // measured 2.5e-5
    EXPECT_LE(w.k, 1e-3);  // measured 5.0e-5
  }
}

TEST(ScreenSphere, GradientNormalsWithinThreePercent) {
  const screen::GBuffer g = sphere_buffer(1024, ortho_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 0.9));
  const auto mask = interior(g, 2);
  for (int edges : {2, 3})
    for (bool lod : {false, true}) {
      screen::ScreenOptions o;
      o.edges = edges, o.lod = lod;
      const screen::ScreenCurvature c = screen::estimate(g, Device::default_device(), o);
      const Worst w = worst_error(c, mask);
      std::vector<double> errs;
      for (std::size_t i = 0; i < mask.size(); ++i)
        if (mask[i] && c.valid[i]) errs.push_back(std::abs(c.H[i] - 1 / kR) * kR);
      std::sort(errs.begin(), errs.end());
      std::printf(
          "sphere gradient normals, %d edges, LOD %s: max rel. error H %.2e K %.2e, "
          "median H %.2e\n",
          edges, lod ? "on" : "off", w.h, w.k, errs[errs.size() / 2]);
      // The spec's 3% for H and K (measured at most 4.1e-3 and 8.3e-3: the normals' error
      // divided by pixel-sized edges); the median measured 6.6e-4, asserted with a 2x margin.
      EXPECT_LE(w.h, 0.03);
      EXPECT_LE(w.k, 0.03);
      EXPECT_LE(errs[errs.size() / 2], 1.5e-3);
    }
}

TEST(ScreenSphere, MelladoWithinOnePercentAwayFromTheSilhouette) {
  const Scene& s = scene("sphere", 256);
  screen::GBuffer g = sphere_buffer(512, ortho_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 0.9));
  exact_normals(g, *s.field);
  screen::ScreenOptions o;
  o.estimator = screen::ScreenEstimator::mellado;
  const auto mask = interior(g, o.mellado_radius + 1);
  const screen::ScreenCurvature c = screen::estimate(g, Device::default_device(), o);
  const Worst w = worst_error(c, mask);
  std::printf("sphere Mellado radius %d: max rel. error H %.2e (%zu px)\n", o.mellado_radius, w.h,
              w.n);
  EXPECT_EQ(w.missing, 0u);
  EXPECT_LE(w.h, 0.01);
}

}  // namespace
}  // namespace isocurv::test
