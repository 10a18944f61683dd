#include "curvature/prantl.h"

#include <cmath>
#include <vector>

#include "core/error.h"
#include "curvature/detail/local_geometry.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"

namespace isocurv::curvature {
namespace {

using detail::V3;

V3 v3(const std::array<double, 3>& a) { return V3(a[0], a[1], a[2]); }

// Eq. 5: the triangle's right-handed frame (Tu, Tv) in its plane.
void triangle_frame(const V3 p[3], V3& tu, V3& tv) {
  tu = (p[1] - p[0]).normalized();
  const V3 m = tu.cross(p[2] - p[0]).normalized();
  tv = m.cross(tu);
}

}  // namespace

bool prantl_triangle(const std::array<std::array<double, 3>, 3>& pa,
                     const std::array<std::array<double, 3>, 3>& na, int edges,
                     TriangleShape& shape) {
  const V3 p[3] = {v3(pa[0]), v3(pa[1]), v3(pa[2])};
  const V3 n[3] = {v3(na[0]), v3(na[1]), v3(na[2])};
  if ((p[1] - p[0]).squaredNorm() == 0 || (p[1] - p[0]).cross(p[2] - p[0]).squaredNorm() == 0)
    return false;
  V3 tu, tv;
  triangle_frame(p, tu, tv);
  // Eq. 7-8 and the sums of the normal equations B (L, M, N)^T = c.
  double sp = 0, sq = 0, sr = 0, c0 = 0, c1 = 0, c2 = 0;
  for (int i = 0; i < edges; ++i) {
    const int j = (i + 1) % 3;
    const V3 e = p[i] - p[j], dn = n[i] - n[j];
    const double u = e.dot(tu), v = e.dot(tv), a = dn.dot(tu), b = dn.dot(tv);
    sp += u * u, sq += u * v, sr += v * v;
    c0 += u * a, c1 += v * a + u * b, c2 += v * b;
  }
  // B = [[p, q, 0], [q, p + r, q], [0, q, r]], det B = (p + r)(pr - q^2).
  const double minor = sp * sr - sq * sq;
  if (!(minor > kPivotTolerance * (sp + sr) * (sp + sr))) return false;
  const double inv_det = 1 / ((sp + sr) * minor);
  // B^-1 = adj(B) / det B (eq. 13 with the corrected (1,1) entry).
  const double i00 = sr * (sp + sr) - sq * sq, i01 = -sq * sr, i02 = sq * sq;
  const double i11 = sp * sr, i12 = -sp * sq, i22 = sp * (sp + sr) - sq * sq;
  shape.L = inv_det * (i00 * c0 + i01 * c1 + i02 * c2);
  shape.M = inv_det * (i01 * c0 + i11 * c1 + i12 * c2);
  shape.N = inv_det * (i02 * c0 + i12 * c1 + i22 * c2);
  return true;
}

CurvatureField estimate_prantl_reference(const Mesh& mesh, const Options& options, int edges,
                                         PrantlAveraging averaging) {
  check_input(mesh, options);
  if (edges != 2 && edges != 3)
    throw Error("curvature: the Prantl estimator takes 2 or 3 edges, not " +
                std::to_string(edges));
  const std::size_t nv = mesh.positions.size();
  const std::vector<V3> normal = detail::vertex_normals(mesh, options);
  CurvatureField out = detail::allocate_field(mesh, /*with_directions=*/false);

  // Per triangle H_f and K_f, accumulated into its corners with weight w_f.
  std::vector<double> sum_h(nv, 0), sum_k(nv, 0), sum_w(nv, 0);
  for (const Tri& t : mesh.triangles) {
    if (detail::repeated_index(t)) continue;
    std::array<std::array<double, 3>, 3> p, n;
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 3; ++c) p[j][c] = mesh.positions[t[j]][c], n[j][c] = normal[t[j]][c];
    TriangleShape s;
    if (!prantl_triangle(p, n, edges, s)) continue;
    const double w = averaging == PrantlAveraging::area
                         ? 0.5 * (v3(p[1]) - v3(p[0])).cross(v3(p[2]) - v3(p[0])).norm()
                         : 1.0;
    for (int j = 0; j < 3; ++j) {
      sum_h[t[j]] += w * s.H();
      sum_k[t[j]] += w * s.K();
      sum_w[t[j]] += w;
    }
  }
  for (std::size_t i = 0; i < nv; ++i) {
    double k1 = 0, k2 = 0;
    if (sum_w[i] > 0) {
      const double h = sum_h[i] / sum_w[i], k = sum_k[i] / sum_w[i];
      const double root = std::sqrt(std::max(0.0, h * h - k));
      k1 = h + root, k2 = h - root;
    } else {
      out.unreliable[i] = 1;
    }
    detail::set_vertex(out, i, normal[i], k1, k2, options.ao_scale);
    // H and K are the averaged ones (k1, k2 only realise them when H^2 >= K).
    if (sum_w[i] > 0) {
      out.H[i] = float(sum_h[i] / sum_w[i]);
      out.K[i] = float(sum_k[i] / sum_w[i]);
    }
  }
  return out;
}

}  // namespace isocurv::curvature
