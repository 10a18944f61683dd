#pragma once
// Small volumes for the mesher tests, sampled from lambdas (independent of datasets/).
#include <cmath>
#include <functional>

#include "volume/from_dense.h"

namespace isocurv::test {

/// Samples f(x, y, z) (world coordinates) on dims voxels with the given spacing and origin.
inline volume::Volume sampled(const std::function<float(double, double, double)>& f, std::array<int, 3> dims,
                              std::array<double, 3> spacing = {1, 1, 1}, std::array<double, 3> origin = {0, 0, 0},
                              volume::Inside inside = volume::Inside::Above) {
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
        data[i++] = f(origin[0] + x * spacing[0], origin[1] + y * spacing[1], origin[2] + z * spacing[2]);
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  m.preScale(openvdb::Vec3d(spacing[0], spacing[1], spacing[2]));
  m.postTranslate(openvdb::Vec3d(origin[0], origin[1], origin[2]));
  auto xf = openvdb::math::Transform::createLinearTransform(m);
  volume::DenseSource src;
  src.path = "test";
  src.format = "generated";
  src.voxel_type = "float";
  src.inside = inside;
  return volume::from_dense(data.data(), dims, xf, src);
}

/// A solid ball of radius r centred at c: density r - |p - c| (inside above 0).
inline volume::Volume ball(int n, double r, double c) {
  return sampled([=](double x, double y, double z) {
    return float(r - std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)));
  }, {n, n, n});
}

/// Torus around the z axis through c: density rt - dist to the core circle of radius R.
inline float torus_density(double x, double y, double z, double R, double rt) {
  double q = std::sqrt(x * x + y * y) - R;
  return float(rt - std::sqrt(q * q + z * z));
}

}  // namespace isocurv::test
