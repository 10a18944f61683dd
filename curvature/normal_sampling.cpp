#include "curvature/normal_sampling.h"

#include <cmath>

#include "curvature/detail/local_geometry.h"

namespace isocurv::curvature {
namespace {

using detail::V3;

constexpr std::size_t kSamplingUnknowns = 3;  // e, f, g

bool fit_normal_curvatures(const detail::VertexRing& r, V3& tensor) {
  const Eigen::Index m = Eigen::Index(r.q.size());
  Eigen::MatrixXd A(m, kSamplingUnknowns);
  Eigen::VectorXd kappa(m), s;
  for (Eigen::Index i = 0; i < m; ++i) {
    const V3 d = r.q[i] - r.p;
    const double tu = d.dot(r.u), tv = d.dot(r.v), len = std::hypot(tu, tv);
    if (!(len > 0)) return false;  // a neighbour straight above P: no direction
    A.row(i) << tu * tu / (len * len), 2 * tu * tv / (len * len), tv * tv / (len * len);
    kappa[i] = -2 * d.dot(r.n) / d.squaredNorm();
  }
  if (!detail::least_squares(A, kappa, s)) return false;
  tensor = V3(s[0], s[1], s[2]);
  return true;
}

}  // namespace

CurvatureField estimate_normal_sampling_reference(const Mesh& mesh, const Options& options) {
  return detail::fit_each_vertex(mesh, options, kSamplingUnknowns, fit_normal_curvatures);
}

}  // namespace isocurv::curvature
