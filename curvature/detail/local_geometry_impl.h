#pragma once
// The template part of local_geometry.h.
#include "curvature/tolerances.h"

namespace isocurv::curvature::detail {

template <int N>
bool ldlt_solve(const Eigen::Matrix<double, N, N>& A, const Eigen::Matrix<double, N, 1>& b,
                Eigen::Matrix<double, N, 1>& x) {
  Eigen::Matrix<double, N, N> L = Eigen::Matrix<double, N, N>::Identity();
  Eigen::Matrix<double, N, 1> d;
  const double tol = kPivotTolerance * A.diagonal().maxCoeff();
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < i; ++j) {
      double s = A(i, j);
      for (int k = 0; k < j; ++k) s -= L(i, k) * L(j, k) * d[k];
      L(i, j) = s / d[j];
    }
    double s = A(i, i);
    for (int k = 0; k < i; ++k) s -= L(i, k) * L(i, k) * d[k];
    if (!(s > tol)) return false;
    d[i] = s;
  }
  Eigen::Matrix<double, N, 1> y = b;
  for (int i = 0; i < N; ++i)  // L y = b
    for (int k = 0; k < i; ++k) y[i] -= L(i, k) * y[k];
  for (int i = 0; i < N; ++i) y[i] /= d[i];  // D z = y
  for (int i = N - 1; i >= 0; --i)           // L^T x = z
    for (int k = i + 1; k < N; ++k) y[i] -= L(k, i) * y[k];
  x = y;
  return true;
}

}  // namespace isocurv::curvature::detail
