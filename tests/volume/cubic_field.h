#pragma once
// A random cubic field in world coordinates and its jet after Gaussian smoothing of covariance
// sigma^2 I, exact (on a cubic only the second moments of a symmetric kernel act): what the
// volume estimator's reconstruction must give at every pyramid level (test_prefilter.cpp,
// test_pyramid.cpp).
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <array>
#include <random>
#include <string>
#include <vector>

#include "volume/gaussian_jet.h"

namespace isocurv::test {

/// p(x) = c + g.x + x'Hx / 2 + T[x, x, x] / 6, x = world - centre.
struct RandomCubic {
  openvdb::Vec3d centre;
  double c = 0, g[3] = {}, H[3][3] = {}, T[3][3][3] = {};

  /// Coefficients uniform in [-1, 1], the Hessian's times h_scale, the third's times t_scale
  /// (drawn from `uni` on `rng` in a fixed order).
  RandomCubic(std::mt19937& rng, std::uniform_real_distribution<double>& uni,
              const openvdb::Vec3d& at, double h_scale, double t_scale)
      : centre(at) {
    c = uni(rng);
    for (double& v : g) v = uni(rng);
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) H[i][j] = H[j][i] = h_scale * uni(rng);
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j)
        for (int k = j; k < 3; ++k) {
          const double t = t_scale * uni(rng);
          T[i][j][k] = T[i][k][j] = T[j][i][k] = T[j][k][i] = T[k][i][j] = T[k][j][i] = t;
        }
  }

  double operator()(const openvdb::Vec3d& w) const {
    const openvdb::Vec3d x = w - centre;
    double v = c;
    for (int i = 0; i < 3; ++i) {
      v += g[i] * x[i];
      for (int j = 0; j < 3; ++j) {
        v += H[i][j] * x[i] * x[j] / 2;
        for (int k = 0; k < 3; ++k) v += T[i][j][k] * x[i] * x[j] * x[k] / 6;
      }
    }
    return v;
  }

  /// The field sampled on `dims` voxels of `xform` (x fastest).
  std::vector<float> sample(const openvdb::math::Transform& xform,
                            const std::array<int, 3>& dims) const {
    std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
    std::size_t n = 0;
    for (int z = 0; z < dims[2]; ++z)
      for (int y = 0; y < dims[1]; ++y)
        for (int x = 0; x < dims[0]; ++x)
          data[n++] = float((*this)(xform.indexToWorld(openvdb::Vec3d(x, y, z))));
    return data;
  }

  /// The jet at w of p smoothed by covariance sigma^2 I: value and gradient pick up sigma^2 / 2
  /// of the Laplacian (a linear function); the Hessian and third derivatives are p's own.
  volume::Jet smoothed(const openvdb::Vec3d& w, double sigma) const {
    const openvdb::Vec3d x = w - centre;
    double trace = 0, lap_grad[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      trace += H[k][k];
      for (int m = 0; m < 3; ++m) lap_grad[m] += T[k][k][m];
    }
    double lap = trace;
    for (int m = 0; m < 3; ++m) lap += lap_grad[m] * x[m];
    volume::Jet j;
    j.value = (*this)(w) + sigma * sigma / 2 * lap;
    for (int k = 0; k < 3; ++k) {
      double grad = g[k] + sigma * sigma / 2 * lap_grad[k];
      for (int q = 0; q < 3; ++q) {
        grad += H[k][q] * x[q];
        for (int m = 0; m < 3; ++m) grad += T[k][q][m] * x[q] * x[m] / 2;
      }
      j.gradient[std::size_t(k)] = grad;
    }
    for (int e = 0; e < 6; ++e) {
      const int k = volume::kHessianAxes[e][0], l = volume::kHessianAxes[e][1];
      double h = H[k][l];
      for (int m = 0; m < 3; ++m) h += T[k][l][m] * x[m];
      j.hessian[std::size_t(e)] = h;
    }
    for (int e = 0; e < 10; ++e)
      j.third[std::size_t(e)] =
          T[volume::kThirdAxes[e][0]][volume::kThirdAxes[e][1]][volume::kThirdAxes[e][2]];
    return j;
  }
};

/// Every component of `got` within its order's tolerance of `want`.
inline void expect_jet_near(const volume::Jet& got, const volume::Jet& want,
                            const std::array<double, 4>& tolerance, const std::string& label) {
  EXPECT_NEAR(got.value, want.value, tolerance[0]) << label;
  for (std::size_t k = 0; k < 3; ++k)
    EXPECT_NEAR(got.gradient[k], want.gradient[k], tolerance[1]) << label << " d/dx" << k;
  for (std::size_t e = 0; e < 6; ++e)
    EXPECT_NEAR(got.hessian[e], want.hessian[e], tolerance[2]) << label << " hessian " << e;
  for (std::size_t e = 0; e < 10; ++e)
    EXPECT_NEAR(got.third[e], want.third[e], tolerance[3]) << label << " third " << e;
}

}  // namespace isocurv::test
