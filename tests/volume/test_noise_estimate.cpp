// volume::estimate_noise: white noise is measured at its deviation, and a smooth field's own
// shape is not taken for noise.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "volume/from_dense.h"
#include "volume/noise_estimate.h"

using namespace isocurv;
using namespace isocurv::volume;

namespace {

// A 64^3 torus (radii 24 and 9 voxels) as a signed distance field plus white Gaussian noise of
// deviation `noise`; points: the voxel centres nearest the surface.
struct Torus {
  Volume volume;
  Positions points;
};

Torus torus(double noise) {
  const int n = 64;
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<float> data(std::size_t(n) * n * n);
  Torus t;
  std::size_t i = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double px = x - 31.7, py = y - 32.2, pz = z - 31.9;
        const double d = std::hypot(std::hypot(px, py) - 24, pz) - 9;
        data[i++] = float(d + noise * gauss(rng));
        if (std::abs(d) < 0.5 && (x + y + z) % 5 == 0)
          t.points.push_back({float(x), float(y), float(z)});
      }
  DenseSource src;
  src.path = "torus";
  src.format = "generated";
  src.voxel_type = "float";
  src.inside = Inside::Below;
  t.volume =
      from_dense(data.data(), {n, n, n}, openvdb::math::Transform::createLinearTransform(1.0), src);
  return t;
}

}  // namespace

TEST(NoiseEstimate, WhiteNoiseAtItsDeviationAndNoneOnASmoothField) {
  const Torus smooth = torus(0);
  const GridFrame f = grid_frame(smooth.volume);
  const NoiseEstimate s = estimate_noise(*smooth.volume.grid, f, smooth.points, 0.0f);
  EXPECT_GT(s.voxels, 10000u);
  // The distance field's step is 1 per voxel; its curvature (tube radius 9) is not noise.
  EXPECT_LT(s.sigma, 5e-4);
  for (double noise : {0.05, 0.2}) {
    const Torus noisy = torus(noise);
    const NoiseEstimate e = estimate_noise(*noisy.volume.grid, f, noisy.points, 0.0f);
    EXPECT_NEAR(e.sigma, noise, 0.1 * noise) << noise;
  }
}
