// G-buffer producer (ii): a mesh rasterised gives the same H image as the volume ray cast of the
// same surface, and the rasteriser's points lie on the mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "core/cl_device.h"
#include "core/mesh_measures.h"
#include "mc/extract.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "tests/screen/scenes.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {

TEST(ScreenMesh, MeshAndVolumeGiveTheSameHImage) {
  const Scene& s = scene("torus", 128);
  const float iso = float(s.field->isovalue());
  const Mesh mesh = mc::extract(s.volume, iso, Device::default_device());
  const auto normals = volume::gradient_normals_for_mesh(s.volume, mesh).normals;
  std::array<double, 6> box;
  ASSERT_TRUE(s.cast->surface_bounds(iso, box));
  const Camera cam = fit_camera(box, ViewSpec{}, 1.0);
  const screen::ViewFrame frame = screen::view_frame(cam, 300, 300);
  const screen::GBuffer gm = screen::rasterise(mesh, normals, frame);
  const screen::GBuffer gv = screen::ray_cast(*s.cast, iso, frame, Device::default_device());
  const auto mm = interior(gm, 2), mv = interior(gv, 2);
  screen::ScreenOptions o;
  const screen::ScreenCurvature cm = screen::estimate(gm, Device::default_device(), o);
  const screen::ScreenCurvature cv = screen::estimate(gv, Device::default_device(), o);
  std::vector<double> diff;
  double scale = 0;
  for (std::size_t i = 0; i < gm.pixels(); ++i)
    if (mm[i] && mv[i] && cm.valid[i] && cv.valid[i]) {
      diff.push_back(std::abs(cm.H[i] - cv.H[i]));
      scale = std::max(scale, double(std::abs(cv.H[i])));
    }
  ASSERT_GT(diff.size(), 10000u);
  std::sort(diff.begin(), diff.end());
  const double med = diff[diff.size() / 2], p90 = diff[diff.size() * 9 / 10];
  std::printf(
      "torus 128^3, 300x300: mesh vs volume H image on %zu px: median |dH| %.3f, p90 %.3f "
      "(max |H| %.2f)\n",
      diff.size(), med, p90, scale);
  // Both see the same surface within a small fraction of a voxel and the same gradient
  // normals; they differ in how normals vary inside a cell (linear on a triangle against the
  // trilinear gradient), which pixel-sized edges magnify: bounded relative to the H range.
  EXPECT_LE(med, 0.01 * scale);
  EXPECT_LE(p90, 0.03 * scale);
  std::size_t both = 0, either = 0;
  for (std::size_t i = 0; i < gm.pixels(); ++i)
    both += gm.valid[i] && gv.valid[i], either += gm.valid[i] || gv.valid[i];
  EXPECT_GE(double(both) / either, 0.98);
}

TEST(ScreenMesh, RasterisedPointsLieOnTheTrianglesAndTheZBufferKeepsTheNearest) {
  // Two squares facing +z at z = 0 and z = 1 (nearer the camera), the nearer one smaller.
  Mesh m;
  m.positions = {{-1, -1, 0},     {1, -1, 0},     {1, 1, 0},     {-1, 1, 0},
                 {-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const std::vector<Vec3f> n(8, Vec3f{0, 0, 1});
  for (bool ortho : {true, false}) {
    Camera cam = ortho_camera({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, 1.2);
    cam.ortho = ortho;
    const screen::GBuffer g = screen::rasterise(m, n, screen::view_frame(cam, 64, 64));
    std::size_t near = 0, far = 0;
    for (std::size_t i = 0; i < g.pixels(); ++i) {
      if (!g.valid[i]) continue;
      const auto& p = g.position[i];
      EXPECT_TRUE(p[2] == 0.0f || std::abs(p[2] - 1.0f) < 1e-6f);
      const bool in_small = std::abs(p[0]) < 0.5 && std::abs(p[1]) < 0.5;
      if (p[2] > 0.5f)
        ++near;
      else
        EXPECT_FALSE(in_small && std::abs(p[0]) < 0.45 && std::abs(p[1]) < 0.45);
      far += p[2] < 0.5f;
      EXPECT_NEAR(g.depth[i], g.frame.eye_depth({p[0], p[1], p[2]}), 1e-5);
    }
    EXPECT_GT(near, 200u);
    EXPECT_GT(far, 1000u);
  }
  EXPECT_THROW(screen::rasterise(m, std::vector<Vec3f>(3), screen::view_frame(Camera{}, 8, 8)),
               Error);
}

}  // namespace
}  // namespace isocurv::test
