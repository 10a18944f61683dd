#include "curvature/batagelo.h"

#include <cstdint>
#include <vector>

#include "curvature/detail/local_geometry.h"
#include "curvature/input.h"

namespace isocurv::curvature {
namespace {

using detail::V3;
using Vec4d = Eigen::Vector4d;

// Step 2: the one-pass tensor (e, f, g) of vertex i in its frame (u, v), each neighbour's rows
// weighted per `weights`. False when the neighbours' projections do not span the plane.
bool one_pass_tensor(std::uint32_t i, const Mesh& mesh, const std::vector<V3>& normal,
                     const detail::Neighbours& nb, const V3& u, const V3& v,
                     curvature::NeighbourWeights weights, V3& tensor) {
  const V3 p = detail::to_v3(mesh.positions[i]);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  V3 rhs = V3::Zero();
  for (std::uint32_t k = nb.offsets[i]; k < nb.offsets[i + 1]; ++k) {
    const std::uint32_t q = nb.ids[k];
    const V3 dx = detail::to_v3(mesh.positions[q]) - p, dn = normal[q] - normal[i];
    const double xu = dx.dot(u), xv = dx.dot(v), yu = dn.dot(u), yv = dn.dot(v);
    const double r2 = xu * xu + xv * xv;
    const double w = weights == curvature::NeighbourWeights::uniform ? 1.0 : r2 > 0 ? 1.0 / r2 : 0.0;
    // Rows [xu xv 0; 0 xu xv] (e, f, g)^T = (yu, yv)^T, times w.
    A(0, 0) += w * xu * xu;
    A(0, 1) += w * xu * xv;
    A(2, 2) += w * xv * xv;
    rhs += w * V3(xu * yu, xv * yu + xu * yv, xv * yv);
  }
  A(1, 1) = A(0, 0) + A(2, 2);
  A(1, 2) = A(2, 1) = A(1, 0) = A(0, 1);
  return detail::ldlt_solve<3>(A, rhs, tensor);
}

// Step 4: the derivative tensor of vertex i in its principal frame (d1, d2).
bool derivative_tensor(std::uint32_t i, const Mesh& mesh, const std::vector<V3>& normal,
                       const detail::Neighbours& nb, const std::vector<detail::Principal>& pr,
                       Vec4d& C) {
  const V3 p = detail::to_v3(mesh.positions[i]);
  const detail::Principal& P = pr[i];
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Vec4d rhs = Vec4d::Zero();
  for (std::uint32_t k = nb.offsets[i]; k < nb.offsets[i + 1]; ++k) {
    const std::uint32_t q = nb.ids[k];
    const V3 dx = detail::to_v3(mesh.positions[q]) - p;
    const double x = dx.dot(P.d1), y = dx.dot(P.d2);
    V3 d1 = pr[q].d1, d2 = pr[q].d2;  // q's principal frame, rotated into P's plane
    if (d1.squaredNorm() == 0) continue;  // q had no tensor
    detail::rotate_to_plane(d1, d2, normal[i]);
    const double a1 = d1.dot(P.d1), b1 = d1.dot(P.d2), a2 = d2.dot(P.d1), b2 = d2.dot(P.d2);
    // q's second fundamental form in P's principal frame, minus P's own (k1, 0, k2).
    const double de = pr[q].k1 * a1 * a1 + pr[q].k2 * a2 * a2 - P.k1;
    const double df = pr[q].k1 * a1 * b1 + pr[q].k2 * a2 * b2;
    const double dg = pr[q].k1 * b1 * b1 + pr[q].k2 * b2 * b2 - P.k2;
    // Rows [x y 0 0] C = de, [0 x y 0] C = df (twice: both off-diagonal entries),
    // [0 0 x y] C = dg.
    A(0, 0) += x * x;
    A(0, 1) += x * y;
    A(1, 1) += 2 * x * x + y * y;
    A(1, 2) += 2 * x * y;
    A(2, 2) += x * x + 2 * y * y;
    A(2, 3) += x * y;
    A(3, 3) += y * y;
    rhs += Vec4d(x * de, y * de + 2 * x * df, 2 * y * df + x * dg, y * dg);
  }
  A(1, 0) = A(0, 1), A(2, 1) = A(1, 2), A(3, 2) = A(2, 3);
  return detail::ldlt_solve<4>(A, rhs, C);
}

}  // namespace

CurvatureField estimate_batagelo_reference(const Mesh& mesh, const Options& options) {
  check_input(mesh, options);
  const std::size_t nv = mesh.positions.size();
  const std::vector<V3> normal = detail::vertex_normals(mesh, options);  // 1
  const detail::Neighbours nb = detail::vertex_neighbours(mesh);
  CurvatureField out = detail::allocate_field(mesh, /*with_directions=*/true);
  out.dcurv.assign(nv, {0, 0, 0, 0});

  std::vector<detail::Principal> pr(nv);
  for (std::uint32_t i = 0; i < nv; ++i) {
    V3 u, v, k = V3::Zero();
    detail::tangent_basis(normal[i], u, v);
    const bool ok = normal[i].squaredNorm() > 0 && one_pass_tensor(i, mesh, normal, nb, u, v, options.batagelo_weights, k);
    if (ok) {
      pr[i] = detail::diagonalise(k[0], k[1], k[2], u, v, normal[i]);  // 3
    } else {
      pr[i].d1 = V3::Zero(), pr[i].d2 = V3::Zero();
      out.unreliable[i] = 1;
    }
    detail::set_vertex(out, i, normal[i], pr[i].k1, pr[i].k2, options.ao_scale);
    out.dir1[i] = detail::to_f3(ok ? pr[i].d1 : u);
    out.dir2[i] = detail::to_f3(ok ? pr[i].d2 : v);
  }
  for (std::uint32_t i = 0; i < nv; ++i) {  // 4
    if (out.unreliable[i]) continue;
    Vec4d C;
    if (derivative_tensor(i, mesh, normal, nb, pr, C))
      out.dcurv[i] = {float(C[0]), float(C[1]), float(C[2]), float(C[3])};
    else
      out.unreliable[i] = 1;
  }
  return out;
}

}  // namespace isocurv::curvature
