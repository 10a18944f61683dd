#include "curvature/auto_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "volume/gaussian_jet.h"
#include "volume/noise_estimate.h"

namespace isocurv::curvature {

ScaleChoice auto_scale(const volume::Volume& volume, const Mesh& mesh, float isovalue) {
  ScaleChoice c;
  const volume::GridFrame frame = volume::grid_frame(volume);
  c.voxel = std::max({frame.spacing[0], frame.spacing[1], frame.spacing[2]});
  c.scale = c.voxel;
  if (mesh.positions.empty() || !volume.grid) return c;
  const std::string& t = volume.voxel_type;
  const bool integer =
      t == "uint8" || t == "int8" || t == "int16" || t == "uint16" || t == "int32" || t == "uint32";
  c.quantisation = integer ? 1 / std::sqrt(12.0) : 0.0;
  c.measured_noise = volume::estimate_noise(*volume.grid, frame, mesh.positions, isovalue).sigma;
  c.noise = std::max(c.measured_noise, c.quantisation);

  const std::size_t n = mesh.positions.size(), take = std::min<std::size_t>(n, 4096);
  std::vector<double> steps;
  steps.reserve(take);
  for (std::size_t k = 0; k < take; ++k) {
    const Vec3f& p = mesh.positions[k * n / take];
    const volume::Jet j =
        volume::gaussian_jet(*volume.grid, frame, openvdb::Vec3d(p[0], p[1], p[2]), c.voxel, 1);
    double len2 = 0;  // index-space gradient: A^T g
    for (int a = 0; a < 3; ++a) {
      double d = 0;
      for (int r = 0; r < 3; ++r) d += frame.A(r, a) * j.gradient[r];
      len2 += d * d;
    }
    if (std::isfinite(len2) && len2 > 0) steps.push_back(std::sqrt(len2));
  }
  if (steps.empty()) return c;
  auto mid = steps.begin() + steps.size() / 2;
  std::nth_element(steps.begin(), mid, steps.end());
  c.edge_step = *mid;
  c.noise_level = c.noise / c.edge_step;
  const double voxels = std::pow(c.noise_level / kAutoReferenceNoise, kAutoScaleExponent);
  c.scale = c.voxel * std::clamp(voxels, kAutoMinVoxels, kAutoMaxVoxels);
  return c;
}

}  // namespace isocurv::curvature
