#include "curvature/auto_scale.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
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

namespace {

// A sample candidate: the hash of its position (52 bits, exact in a double), then the position,
// which breaks ties.
using Sample = std::tuple<double, float, float, float>;

Sample sample_of(const Vec3f& p) {
  std::uint32_t b[3];
  std::memcpy(b, p.data(), sizeof b);
  std::uint64_t h = (std::uint64_t(b[0]) << 32 | b[1]) ^ (std::uint64_t(b[2]) * 0x9e3779b97f4a7c15ull);
  h ^= h >> 33, h *= 0xff51afd7ed558ccdull, h ^= h >> 33, h *= 0xc4ceb9fe1a85ec53ull, h ^= h >> 33;
  return {double(h >> 12), p[0], p[1], p[2]};
}

// Keeps the kEdgeSamples candidates of `v` that hash lowest, sorted.
void keep_lowest(std::vector<Sample>& v) {
  if (v.size() > kEdgeSamples) {
    std::nth_element(v.begin(), v.begin() + kEdgeSamples, v.end());
    v.resize(kEdgeSamples);
  }
  std::sort(v.begin(), v.end());
}

// The lowest of every piece's lowest `mine`: the whole surface's lowest.
std::vector<Sample> lowest_of_all(const std::vector<Sample>& mine, const SurfacePiece& piece) {
  std::vector<double> flat;
  for (const auto& [h, x, y, z] : mine) flat.insert(flat.end(), {h, x, y, z});
  const std::vector<double> every = piece.all(flat);
  std::vector<Sample> all;
  for (std::size_t i = 0; i + 3 < every.size(); i += 4)
    all.emplace_back(every[i], float(every[i + 1]), float(every[i + 2]), float(every[i + 3]));
  keep_lowest(all);
  return all;
}

}  // namespace

ScaleChoice auto_scale(const volume::Volume& volume, const Mesh& mesh, float isovalue,
                       const SurfacePiece* piece) {
  ScaleChoice c;
  const volume::GridFrame frame = volume::grid_frame(volume);
  const double largest = std::max({frame.spacing[0], frame.spacing[1], frame.spacing[2]});
  c.voxel = std::cbrt(frame.spacing[0] * frame.spacing[1] * frame.spacing[2]);
  // No axis under the reconstruction's floor (a little above it, for rounding).
  const double floor = 1.01 * volume::kMinScaleVoxels * largest;
  c.model.cell_volume = frame.spacing[0] * frame.spacing[1] * frame.spacing[2];
  auto finish = [&](double voxels) {
    c.scale = std::max(c.voxel * voxels, floor);
    c.model.noise = c.noise;
    return c;
  };
  if (total_count(piece, mesh.positions.size()) == 0 || !volume.grid) return finish(1.0);
  if (is_binary(volume)) {
    c.binary = true;
    c.noise = kBinaryNoise * (volume.stats.max - volume.stats.min);
    c.model.shape_scale = kBinaryShapeScale;
    c.model.staircase = true;
    return finish(kBinaryScaleVoxels);
  }
  c.quantisation = volume::is_integer_type(volume.voxel_type) ? 1 / std::sqrt(12.0) : 0.0;
  Positions own;  // the vertices this piece counts (all of them without a piece)
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (owns_vertex(piece, v)) own.push_back(mesh.positions[v]);
  c.measured_noise = volume::estimate_noise(*volume.grid, frame, own, isovalue, 64, piece).sigma;
  c.noise = std::max(c.measured_noise, c.quantisation);

  std::vector<Sample> lowest;
  lowest.reserve(own.size());
  for (const Vec3f& p : own) lowest.push_back(sample_of(p));
  keep_lowest(lowest);
  std::map<Sample, int> unmeasured;  // this piece's lowest: it measures those chosen
  if (piece)
    for (const Sample& s : lowest) ++unmeasured[s];
  std::vector<double> steps;
  for (const Sample& s : piece ? lowest_of_all(lowest, *piece) : lowest) {
    if (piece) {
      const auto it = unmeasured.find(s);
      if (it == unmeasured.end() || it->second == 0) continue;  // another piece's vertex
      --it->second;
    }
    const Vec3f p{std::get<1>(s), std::get<2>(s), std::get<3>(s)};
    const volume::Jet j =
        volume::gaussian_jet(*volume.grid, frame, openvdb::Vec3d(p[0], p[1], p[2]), c.voxel, 1);
    const double len2 = j.gradient[0] * j.gradient[0] + j.gradient[1] * j.gradient[1] +
                        j.gradient[2] * j.gradient[2];
    if (std::isfinite(len2) && len2 > 0) steps.push_back(std::sqrt(len2) * c.voxel);
  }
  if (piece) steps = piece->all(steps);  // the median is the same in any order
  if (steps.empty()) return finish(1.0);
  auto mid = steps.begin() + steps.size() / 2;
  std::nth_element(steps.begin(), mid, steps.end());
  c.edge_step = *mid;
  c.noise_level = c.noise / c.edge_step;
  const double voxels = std::pow(c.noise_level / kAutoReferenceNoise, kAutoScaleExponent);
  return finish(std::clamp(voxels, kAutoMinVoxels, kAutoMaxVoxels));
}

}  // namespace isocurv::curvature
