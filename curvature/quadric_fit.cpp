#include "curvature/quadric_fit.h"

#include "curvature/detail/local_geometry.h"

namespace isocurv::curvature {
namespace {

using detail::V3;

constexpr std::size_t kQuadricUnknowns = 3;  // a, b, c

bool fit_quadric(const detail::VertexRing& r, V3& tensor) {
  const Eigen::Index m = Eigen::Index(r.q.size());
  Eigen::MatrixXd A(m, kQuadricUnknowns);
  Eigen::VectorXd z(m), s;
  for (Eigen::Index i = 0; i < m; ++i) {
    const V3 d = r.q[i] - r.p;
    const double x = d.dot(r.u), y = d.dot(r.v);
    A.row(i) << x * x / 2, x * y, y * y / 2;
    z[i] = d.dot(r.n);
  }
  if (!detail::least_squares(A, z, s)) return false;
  tensor = -V3(s[0], s[1], s[2]);
  return true;
}

}  // namespace

CurvatureField estimate_quadric_fit_reference(const Mesh& mesh, const Options& options) {
  return detail::fit_each_vertex(mesh, options, kQuadricUnknowns, fit_quadric);
}

}  // namespace isocurv::curvature
