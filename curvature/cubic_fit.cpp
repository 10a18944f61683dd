#include "curvature/cubic_fit.h"

#include "curvature/detail/local_geometry.h"

namespace isocurv::curvature {
namespace {

using detail::V3;

constexpr int kCubicUnknowns = 7;              // A, B, C, D, E, F, G
constexpr std::size_t kMinNeighbours = 3;  // 9 rows for 7 unknowns
constexpr double kMinNormalZ = 0.1;       // m_n below this: the slope rows are dropped

bool fit_cubic(const detail::VertexRing& r, V3& tensor) {
  // Rows in world units, as Goldfeather and Interrante write them: a position residual (a length,
  // ~ edge^2 curvature) then weighs far less than a slope residual (~ edge curvature), so the
  // fit follows the normals, which is what keeps it stable under displacement noise (Batagelo
  // Fig. 3). least_squares scales the columns for conditioning only.
  Eigen::MatrixXd A(3 * r.q.size(), kCubicUnknowns);
  Eigen::VectorXd b(3 * r.q.size()), s;
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < r.q.size(); ++i) {
    const V3 d = r.q[i] - r.p;
    const double x = d.dot(r.u), y = d.dot(r.v);
    A.row(row) << x * x / 2, x * y, y * y / 2, x * x * x, x * x * y, x * y * y, y * y * y;
    b[row++] = d.dot(r.n);
    const double mu = r.nq[i].dot(r.u), mv = r.nq[i].dot(r.v), mn = r.nq[i].dot(r.n);
    if (!(mn >= kMinNormalZ)) continue;
    A.row(row) << x, y, 0, 3 * x * x, 2 * x * y, y * y, 0;
    b[row++] = -mu / mn;
    A.row(row) << 0, x, y, 0, x * x, 2 * x * y, 3 * y * y;
    b[row++] = -mv / mn;
  }
  if (!detail::least_squares(A.topRows(row), b.head(row), s)) return false;
  tensor = -V3(s[0], s[1], s[2]);
  return true;
}

}  // namespace

CurvatureField estimate_cubic_fit_reference(const Mesh& mesh, const Options& options) {
  return detail::fit_each_vertex(mesh, options, kMinNeighbours, fit_cubic);
}

}  // namespace isocurv::curvature
