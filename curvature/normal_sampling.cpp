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
  Eigen::Index rows = 0;
  double largest = 0;
  for (const V3& q : r.q) {
    const V3 d = q - r.p;
    const double tu = d.dot(r.u), tv = d.dot(r.v), len = std::hypot(tu, tv);
    if (!(len > 0)) continue;  // a neighbour straight above P: no direction
    const double k = -2 * d.dot(r.n) / d.squaredNorm();
    if (!detail::keep_sample(k, r, largest)) continue;
    A.row(rows) << tu * tu / (len * len), 2 * tu * tv / (len * len), tv * tv / (len * len);
    kappa[rows++] = k;
  }
  if (!detail::least_squares(A.topRows(rows), kappa.head(rows), s)) return false;
  tensor = V3(s[0], s[1], s[2]);
  return detail::determined_by_samples(tensor, largest, r);
}

}  // namespace

CurvatureField estimate_normal_sampling_reference(const Mesh& mesh, const Options& options) {
  return detail::fit_each_vertex(mesh, options, kSamplingUnknowns, fit_normal_curvatures);
}

}  // namespace isocurv::curvature
