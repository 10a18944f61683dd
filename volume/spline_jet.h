#pragma once
// The second half of the volume estimator's reconstruction (the first is volume/prefilter.h): the
// field F(q) = sum_i S_i beta4(q - i) and its derivatives up to the third at any point, from the
// smoothed samples S and the centred quartic B-spline beta4 (C3: the third derivatives, which the
// curvature derivative needs, are continuous). The double-precision specification that
// curvature/volume_kernels.cl (spline_jet) follows.
// Tested in tests/volume/test_prefilter.cpp.
#include "volume/gaussian_jet.h"
#include "volume/prefilter.h"

namespace isocurv::volume {

/// The quartic B-spline's weights along one axis at index coordinate q: taps first .. first + 4
/// (first = floor(q + 2.5) - 4), w[n][t] = d^n/dq^n beta4(q - first - t) for n = 0..3. The
/// weights of each order sum to the n-th derivative of 1 (1, 0, 0, 0) and are exact on
/// polynomials up to degree 4 in the sense of Strang and Fix (their discrete moments do not
/// depend on q).
struct SplineWeights {
  static constexpr int count = 5;
  int first = 0;
  double w[4][5] = {};
};

/// The weights at q (index units).
SplineWeights spline_weights(double q);

/// The jet of F at world point p: derivatives above `order` (0..3) are zero. Reads only
/// s.plan->stages[3]'s bricks, which cover every point the plan was made for (and anything within
/// its reach). Thread-safe.
Jet spline_jet(const SmoothedSamples& s, const openvdb::Vec3d& p, int order = 3);

}  // namespace isocurv::volume
