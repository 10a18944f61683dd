#pragma once
// What the features tests share: array lookup, error against exact values, a marching-cubes
// surface of a volume with the curvature reference's field, and a CT-like ball.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "curvature/reference.h"
#include "features/features.h"
#include "mc/extract_reference.h"
#include "volume/from_dense.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {

inline const std::vector<float>& array(const features::FeatureField& f, const std::string& name) {
  for (const auto& a : f.arrays)
    if (a.name == name) return a.values;
  ADD_FAILURE() << "no array " << name;
  static const std::vector<float> none;
  return none;
}

/// Mean and relative RMS of `values` against `exact` over the vertices not
/// flagged Boundary.
struct Error2 {
  double mean = 0, rel_rms = 0;
  std::size_t count = 0;
};
inline Error2 compare(const std::vector<float>& values, const std::vector<double>& exact,
                      const std::vector<std::uint8_t>& boundary) {
  Error2 e;
  double se = 0, sr = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (boundary[i]) continue;
    e.mean += values[i];
    se += (values[i] - exact[i]) * (values[i] - exact[i]);
    sr += exact[i] * exact[i];
    ++e.count;
  }
  if (e.count) e.mean /= double(e.count);
  e.rel_rms = sr > 0 ? std::sqrt(se / sr) : std::sqrt(se / std::max<std::size_t>(1, e.count));
  return e;
}

/// The mesh, volume normals and areas of a volume's isosurface.
struct VolumeSurface {
  volume::Volume volume;
  Mesh mesh;
  curvature::CurvatureField field;
  double iso = 0;
};
inline VolumeSurface surface_of(volume::Volume v, double iso) {
  VolumeSurface s{std::move(v), {}, {}, iso};
  s.mesh = mc::extract_reference(s.volume, float(iso));
  const volume::MeshNormals n = volume::gradient_normals_for_mesh(s.volume, s.mesh);
  curvature::Options o;
  o.vertex_normals = &n.normals;
  s.field = curvature::estimate_reference(s.mesh, o);
  return s;
}

/// A CT-like ball: radius R voxels in an n^3 volume, edge blurred (Gaussian,
/// sigma 1 voxel), 20 outside and 220 inside, uniform noise of +-4 grey levels,
/// quantised to uint8.
inline volume::Volume ct_ball(int n, double R) {
  std::vector<float> data(std::size_t(n) * n * n);
  std::uint32_t seed = 12345;
  std::size_t i = 0;
  const double c = 0.5 * (n - 1);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double r = std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c));
        seed = seed * 1664525u + 1013904223u;
        const double noise = (double(seed >> 8) / double(1u << 24) - 0.5) * 8;
        const double v = 20 + 200 * 0.5 * (1 + std::erf((R - r) / std::sqrt(2.0))) + noise;
        data[i++] = float(std::lround(std::clamp(v, 0.0, 255.0)));
      }
  volume::DenseSource src{"generated:ct_ball", "generated", "uint8", "density",
                          volume::Inside::Above};
  return volume::from_dense(data.data(), {n, n, n},
                            openvdb::math::Transform::createLinearTransform(1.0), src);
}

}  // namespace isocurv::test
