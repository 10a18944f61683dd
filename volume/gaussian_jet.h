#pragma once
// Derivatives of a volume at a scale by direct Gaussian derivative filters: the value, gradient,
// Hessian and third derivatives of the volume's samples convolved with a Gaussian of standard
// deviation sigma (world units), evaluated at any world point, each tap read from the grid (the
// automatic scale's edge measure uses it). Also the grid frame, the jet type and its Taylor shift
// that the volume estimator's reconstruction (volume/prefilter.h, volume/spline_jet.h) shares.
// Tested in tests/volume/test_noise_estimate.cpp (through its users).
#include <openvdb/openvdb.h>

#include <array>

#include "volume/volume.h"

namespace isocurv::volume {

/// Taps of each 1-D filter reach this many standard deviations from the evaluation point: the
/// second and third derivatives' tails are heavy (at 3.5 deviations the truncated filters missed
/// their moments by percents and biased the curvature as much; at 5 by about 1e-4).
inline constexpr double kGaussianRadius = 5.0;

/// Value and derivatives at one point, in world coordinates. Symmetric tensors are stored by their
/// distinct components: hessian (xx, xy, xz, yy, yz, zz); third (xxx, xxy, xxz, xyy, xyz, xzz,
/// yyy, yyz, yzz, zzz).
struct Jet {
  double value = 0;
  std::array<double, 3> gradient{};
  std::array<double, 6> hessian{};
  std::array<double, 10> third{};
};

/// The axes of each stored Hessian component (xx, xy, xz, yy, yz, zz) and third-derivative
/// component (xxx, xxy, ..., zzz), in Jet's order.
inline constexpr int kHessianAxes[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
inline constexpr int kThirdAxes[10][3] = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 1, 1}, {0, 1, 2},
                                          {0, 2, 2}, {1, 1, 1}, {1, 1, 2}, {1, 2, 2}, {2, 2, 2}};

/// How index space maps to world space for the reconstruction: world = origin + A * index, where
/// the columns of A (the index axes in world space) must be orthogonal (spacing times a rotation,
/// as NIfTI, NRRD and MetaImage direction matrices are), so that a Gaussian isotropic in world
/// space is separable along the index axes with per-axis deviation sigma / |column|.
struct GridFrame {
  openvdb::Mat3d A;        ///< index -> world linear part (column a: index axis a in world space)
  openvdb::Mat3d B;        ///< A^-1 (world -> index)
  openvdb::Vec3d origin;   ///< world position of index (0, 0, 0)
  openvdb::Vec3d spacing;  ///< |column a| of A
  bool clamp = false;      ///< true for dense volumes: indices are clamped to the domain
  openvdb::Coord lo, hi;   ///< the domain (inclusive) when clamping

  openvdb::Vec3d to_index(const openvdb::Vec3d& world) const { return B * (world - origin); }
  openvdb::Vec3d to_world(const openvdb::Vec3d& index) const { return origin + A * index; }
};

/// The frame of `volume`'s grid transform. Throws isocurv::Error when the transform is not affine
/// or its axes are not orthogonal (a sheared grid), naming the volume's file.
GridFrame grid_frame(const Volume& volume);

/// Per-axis filter weights at one evaluation coordinate q (index units) for deviation s (index
/// units): taps j = first .. first + count - 1 cover |j - q| <= radius * s, and w[n][t] is
/// the n-th derivative (n = 0..3) of the Gaussian G(q - j) at tap first + t, each order scaled by
/// one factor so that it is exact on the monomial (j - q)^n / n! (a correction of the sampling and
/// the truncation of 1e-4 or less for s >= 0.7). The filters stay isotropic: an exactness
/// correction per axis (making them exact on all cubics) was tried and biased blurred edges by
/// 20%, since the product of corrected 1-D filters is no longer rotation invariant.
struct AxisWeights {
  int first = 0, count = 0;
  static constexpr int kMaxTaps = 64;
  double w[4][kMaxTaps];
};

/// The weights of AxisWeights for coordinate q and deviation s (0 < s <= kMaxDeviation).
AxisWeights axis_weights(double q, double s, double radius = kGaussianRadius);

/// The largest per-axis deviation in index units axis_weights accepts (taps stay <= kMaxTaps).
inline constexpr double kMaxDeviation = 6.0;

/// The jet of `volume` smoothed at world deviation `sigma` at world point `p`; derivatives above
/// `order` (0..3) are left zero; the filters reach `radius` deviations (3 are enough for
/// order <= 1, whose filters' tails are light). Samples outside a dense volume's domain repeat the
/// nearest domain sample; a sparse grid's inactive voxels read as its background. Thread-safe.
Jet gaussian_jet(const openvdb::FloatGrid& grid, const GridFrame& frame, const openvdb::Vec3d& p,
                 double sigma, int order = 3, double radius = kGaussianRadius);

/// The world-space jet from index-space derivatives d[nx][ny][nz] (of orders nx, ny, nz along the
/// index axes; only nx + ny + nz <= order are read) for the world -> index matrix B.
Jet world_jet(const double (&d)[4][4][4], const openvdb::Mat3d& B, int order);

/// The jet's Taylor expansion moved by a small world-space `step`: the value to third order, the
/// gradient to second, the Hessian to first, the third derivatives unchanged.
Jet shifted_jet(const Jet& jet, const openvdb::Vec3d& step);

}  // namespace isocurv::volume
