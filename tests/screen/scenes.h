#pragma once
// Shared scenes for the screen tests: analytic fields sampled into cast volumes, cameras, the
// interior-pixel mask, exact normals and per-pixel errors against the analytic curvature.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "screen/estimate.h"
#include "screen/gbuffer.h"
#include "volume/dense_field.h"

namespace isocurv::test {

/// A field and its volume at `resolution`, built once per process (sampling 256^3 takes a while).
struct Scene {
  std::unique_ptr<datasets::Field> field;
  volume::Volume volume;
  std::unique_ptr<volume::DenseField> cast;
};
inline const Scene& scene(const std::string& name, int resolution) {
  static std::map<std::pair<std::string, int>, std::unique_ptr<Scene>> cache;
  auto& s = cache[{name, resolution}];
  if (!s) {
    s = std::make_unique<Scene>();
    s->field = datasets::make_field(name);
    s->volume = datasets::sample(*s->field, resolution);
    s->cast = std::make_unique<volume::DenseField>(s->volume);
  }
  return *s;
}

/// An orthographic camera looking along -toward at `centre`, parallel scale `half` (world).
inline Camera ortho_camera(const std::array<double, 3>& centre, const std::array<double, 3>& toward,
                           const std::array<double, 3>& up, double half, double distance = 5) {
  Camera c;
  c.ortho = true;
  c.focal_point = centre;
  for (int k = 0; k < 3; ++k) c.position[k] = centre[k] + distance * toward[k];
  c.view_up = up;
  c.parallel_scale = half;
  return c;
}

/// Valid pixels whose (2r+1)^2 neighbourhood is all valid: at least r pixels from a silhouette.
inline std::vector<std::uint8_t> interior(const screen::GBuffer& g, int r) {
  std::vector<std::uint8_t> m(g.pixels(), 0);
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x) {
      bool ok = true;
      for (int j = -r; j <= r && ok; ++j)
        for (int i = -r; i <= r && ok; ++i) {
          const int qx = x + i, qy = y + j;
          ok = qx >= 0 && qy >= 0 && qx < g.width() && qy < g.height() &&
               g.valid[qx + g.width() * qy];
        }
      m[x + g.width() * y] = ok;
    }
  return m;
}

/// Replaces the G-buffer's normals by the field's exact outward normals at its points.
inline void exact_normals(screen::GBuffer& g, const datasets::Field& f) {
  const double s = f.inside() == volume::Inside::Above ? -1 : 1;
  for (std::size_t i = 0; i < g.pixels(); ++i) {
    if (!g.valid[i]) continue;
    const auto& p = g.position[i];
    const Eigen::Vector3d n = s * f.gradient(Eigen::Vector3d(p[0], p[1], p[2])).normalized();
    g.normal[i] = {float(n.x()), float(n.y()), float(n.z())};
  }
}

/// Mean squared error of H and K over the pixels of `mask` that were estimated, against the
/// field's exact curvature at each pixel's surface point (projected onto the exact surface).
struct Mse {
  double H = 0, K = 0;
  std::size_t n = 0;
};
inline Mse mse_against_field(const screen::GBuffer& g, const screen::ScreenCurvature& c,
                             const datasets::Field& f, const std::vector<std::uint8_t>& mask) {
  Mse m;
  for (std::size_t i = 0; i < g.pixels(); ++i) {
    if (!mask[i] || !c.valid[i]) continue;
    const auto& p = g.position[i];
    const Eigen::Vector3d q = datasets::project_to_surface(f, Eigen::Vector3d(p[0], p[1], p[2]));
    const datasets::SurfaceCurvature e = datasets::exact_curvature(f, q);
    m.H += (c.H[i] - e.H) * (c.H[i] - e.H), m.K += (c.K[i] - e.K) * (c.K[i] - e.K), ++m.n;
  }
  if (m.n) m.H /= m.n, m.K /= m.n;
  return m;
}

}  // namespace isocurv::test
