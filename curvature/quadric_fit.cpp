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
  Eigen::Index rows = 0;
  double largest = 0;
  for (const V3& q : r.q) {
    const V3 d = q - r.p;
    const double x = d.dot(r.u), y = d.dot(r.v), h = d.dot(r.n);
    // the sample's normal curvature: the osculating parabola's through q in its direction
    if (!detail::keep_sample(-2 * h / (x * x + y * y), r, largest)) continue;
    A.row(rows) << x * x / 2, x * y, y * y / 2;
    z[rows++] = h;
  }
  if (!detail::least_squares(A.topRows(rows), z.head(rows), s)) return false;
  tensor = -V3(s[0], s[1], s[2]);
  return detail::determined_by_samples(tensor, largest, r);
}

}  // namespace

CurvatureField estimate_quadric_fit_reference(const Mesh& mesh, const Options& options) {
  return detail::fit_each_vertex(mesh, options, kQuadricUnknowns, fit_quadric);
}

}  // namespace isocurv::curvature
