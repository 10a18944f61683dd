#include "curvature/auto_scale.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "volume/gaussian_jet.h"
#include "volume/noise_estimate.h"
#include "volume/prefilter.h"

namespace isocurv::curvature {

bool is_binary(const volume::Volume& volume) {
  const std::vector<std::uint64_t>& h = volume.stats.histogram;
  std::size_t used = 0;
  for (std::uint64_t n : h) used += n > 0;
  return volume.stats.max > volume.stats.min && used == 2 && h.front() > 0 && h.back() > 0;
}

ScaleChoice auto_scale(const volume::Volume& volume, const Mesh& mesh, float isovalue) {
  ScaleChoice c;
  const volume::GridFrame frame = volume::grid_frame(volume);
  const double largest = std::max({frame.spacing[0], frame.spacing[1], frame.spacing[2]});
  c.voxel = std::cbrt(frame.spacing[0] * frame.spacing[1] * frame.spacing[2]);
  // No axis under the reconstruction's floor (a little above it, for rounding).
  const double floor = 1.01 * volume::kMinScaleVoxels * largest;
  auto finish = [&](double voxels) {
    c.scale = std::max(c.voxel * voxels, floor);
    return c;
  };
  if (mesh.positions.empty() || !volume.grid) return finish(1.0);
  if (is_binary(volume)) {
    c.binary = true;
    return finish(kBinaryScaleVoxels);
  }
  const std::string& t = volume.voxel_type;
  const bool integer =
      t == "uint8" || t == "int8" || t == "int16" || t == "uint16" || t == "int32" || t == "uint32";
  c.quantisation = integer ? 1 / std::sqrt(12.0) : 0.0;
  c.measured_noise = volume::estimate_noise(*volume.grid, frame, mesh.positions, isovalue, 64).sigma;
  c.noise = std::max(c.measured_noise, c.quantisation);

  const std::size_t n = mesh.positions.size(), take = std::min<std::size_t>(n, 1024);
  std::vector<double> steps;
  steps.reserve(take);
  for (std::size_t k = 0; k < take; ++k) {
    const Vec3f& p = mesh.positions[k * n / take];
    const volume::Jet j =
        volume::gaussian_jet(*volume.grid, frame, openvdb::Vec3d(p[0], p[1], p[2]), c.voxel, 1);
    const double len2 = j.gradient[0] * j.gradient[0] + j.gradient[1] * j.gradient[1] +
                        j.gradient[2] * j.gradient[2];
    if (std::isfinite(len2) && len2 > 0) steps.push_back(std::sqrt(len2) * c.voxel);
  }
  if (steps.empty()) return finish(1.0);
  auto mid = steps.begin() + steps.size() / 2;
  std::nth_element(steps.begin(), mid, steps.end());
  c.edge_step = *mid;
  c.noise_level = c.noise / c.edge_step;
  const double voxels = std::pow(c.noise_level / kAutoReferenceNoise, kAutoScaleExponent);
  return finish(std::clamp(voxels, kAutoMinVoxels, kAutoMaxVoxels));
}

}  // namespace isocurv::curvature
