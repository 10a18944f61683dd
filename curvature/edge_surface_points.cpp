// VolumePoint::vertex's surface points: marching-cubes vertices moved along their cube edges by
// the surface's curvature (see edge_surface_points in volume_estimate.h).
#include <algorithm>
#include <cmath>

#include "curvature/volume_estimate.h"
#include "volume/gaussian_jet.h"

namespace isocurv::curvature {

std::vector<Vec3f> edge_surface_points(const Mesh& mesh, const volume::Volume& volume,
                                       const CurvatureField& field) {
  const std::size_t nv = mesh.positions.size();
  std::vector<Vec3f> out(mesh.positions.begin(), mesh.positions.end());
  if (field.normals.size() != nv || field.k1.size() != nv || field.k2.size() != nv ||
      field.dir1.size() != nv || field.dir2.size() != nv || !volume.grid)
    return out;
  const volume::GridFrame frame = volume::grid_frame(volume);
  constexpr double kWhole = 1e-3;  // index units: a coordinate this near an integer is whole
  constexpr double kMaxRatio = 0.5;
  for (std::size_t i = 0; i < nv; ++i) {
    if (field.unreliable.size() == nv && field.unreliable[i]) continue;
    const Vec3f& p = mesh.positions[i];
    const openvdb::Vec3d q = frame.to_index(openvdb::Vec3d(p[0], p[1], p[2]));
    int axis = -1, fractional = 0;
    double s = 0;
    for (int a = 0; a < 3; ++a) {
      const double f = q[a] - std::floor(q[a]);
      if (std::min(f, 1 - f) > kWhole) ++fractional, axis = a, s = f;
    }
    if (fractional != 1) continue;
    const openvdb::Vec3d col(frame.A(0, axis), frame.A(1, axis), frame.A(2, axis));
    const double h = col.length();
    const openvdb::Vec3d e = col / h;
    const auto dot = [&](const Vec3f& v) { return e[0] * v[0] + e[1] * v[1] + e[2] * v[2]; };
    const double c = dot(field.normals[i]);
    const double d1 = dot(field.dir1[i]), d2 = dot(field.dir2[i]);
    const double kappa = double(field.k1[i]) * d1 * d1 + double(field.k2[i]) * d2 * d2;
    if (!std::isfinite(kappa) || !(std::abs(c) > 0)) continue;
    const double ratio = std::clamp(kappa * h / (2 * c), -kMaxRatio, kMaxRatio);
    const double move = ratio * h * s * (1 - s);
    out[i] = {float(p[0] + move * e[0]), float(p[1] + move * e[1]), float(p[2] + move * e[2])};
  }
  return out;
}

}  // namespace isocurv::curvature
