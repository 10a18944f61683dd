#include "curvature/reference.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "curvature/derived.h"
#include "curvature/input.h"
#include "curvature/mesh_areas.h"
#include "curvature/tolerances.h"

namespace isocurv::curvature {
namespace {

using V3 = Eigen::Vector3d;
using Vec4d = Eigen::Vector4d;

V3 to_v3(const Vec3f& p) { return V3(p[0], p[1], p[2]); }
Vec3f to_f3(const V3& v) { return {float(v.x()), float(v.y()), float(v.z())}; }
int next(int j) { return j == 2 ? 0 : j + 1; }
int prev(int j) { return j == 0 ? 2 : j - 1; }
bool repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// Solves the symmetric system A x = b by LDL^T (no pivoting). False when a pivot is not above
// kPivotTolerance times the largest diagonal entry: the triangle's edges do not span a plane.
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
  x = b;
  for (int i = 0; i < N; ++i)  // L y = b
    for (int k = 0; k < i; ++k) x[i] -= L(i, k) * x[k];
  for (int i = 0; i < N; ++i) x[i] /= d[i];  // D z = y
  for (int i = N - 1; i >= 0; --i)  // L^T x = z
    for (int k = i + 1; k < N; ++k) x[i] -= L(k, i) * x[k];
  return true;
}

// Mixed corner areas (curvature/mesh_areas.h) of the triangle p.
std::array<double, 3> corner_areas(const V3 p[3]) {
  return mixed_corner_areas({{{p[0].x(), p[0].y(), p[0].z()},
                              {p[1].x(), p[1].y(), p[1].z()},
                              {p[2].x(), p[2].y(), p[2].z()}}});
}

// An orthonormal tangent basis (u, v) with (u, v, n) right-handed, from the unit normal alone
// (Duff et al., "Building an orthonormal basis, revisited", 2017).
void tangent_basis(const V3& n, V3& u, V3& v) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  u = V3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  v = V3(b, sign + n.y() * n.y() * a, -n.y());
}

// Rotates the tangent pair (u, v) of unit normal u x v about u x v -> n, the smallest rotation
// taking that normal onto n. For opposite normals, a half turn about u.
void rotate_to_plane(V3& u, V3& v, const V3& n) {
  const V3 old_n = u.cross(v);
  const double ndot = old_n.dot(n);
  if (1 + ndot < kOppositeNormals) {
    v = -v;
    return;
  }
  const V3 perp = n - ndot * old_n;
  const V3 dperp = (old_n + n) / (1 + ndot);
  u -= dperp * u.dot(perp);
  v -= dperp * v.dot(perp);
}

// Coordinates of the frame (new_u, new_v) in the frame (old_u, old_v), after rotating the new
// frame into the old one's plane: rows x1 = (u1, v1) and x2 = (u2, v2).
Eigen::Matrix2d frame_change(const V3& old_u, const V3& old_v, V3 new_u, V3 new_v) {
  rotate_to_plane(new_u, new_v, old_u.cross(old_v));
  Eigen::Matrix2d x;
  x << new_u.dot(old_u), new_u.dot(old_v), new_v.dot(old_u), new_v.dot(old_v);
  return x;
}

// A symmetric 2-tensor (ku, kuv, kv) expressed in the frame whose axes have coordinates x.row(i).
V3 change_tensor(const V3& k, const Eigen::Matrix2d& x) {
  const Eigen::Matrix2d T = (Eigen::Matrix2d() << k[0], k[1], k[1], k[2]).finished();
  const Eigen::Matrix2d R = x * T * x.transpose();
  return V3(R(0, 0), R(0, 1), R(1, 1));
}

// The symmetric 3-tensor C = (C111, C112, C122, C222) evaluated on three 2-vectors.
double cubic_form(const Vec4d& C, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                  const Eigen::Vector2d& r) {
  return C[0] * p[0] * q[0] * r[0] +
         C[1] * (p[0] * q[0] * r[1] + p[0] * q[1] * r[0] + p[1] * q[0] * r[0]) +
         C[2] * (p[0] * q[1] * r[1] + p[1] * q[0] * r[1] + p[1] * q[1] * r[0]) +
         C[3] * p[1] * q[1] * r[1];
}

Vec4d change_cubic(const Vec4d& C, const Eigen::Matrix2d& x) {
  const Eigen::Vector2d x1 = x.row(0), x2 = x.row(1);
  return Vec4d(cubic_form(C, x1, x1, x1), cubic_form(C, x1, x1, x2), cubic_form(C, x1, x2, x2),
               cubic_form(C, x2, x2, x2));
}

}  // namespace

CurvatureField estimate_reference(const Mesh& mesh, const Options& options) {
  check_input(mesh, options);
  const std::size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  auto P = [&](std::uint32_t i) { return to_v3(mesh.positions[i]); };

  // 1-2. Normals and mixed corner areas.
  std::vector<std::array<double, 3>> corner_area(nf, {0, 0, 0});
  std::vector<V3> normal(nv, V3::Zero());
  std::vector<double> area(nv, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.triangles[f];
    if (repeated_index(t)) continue;
    const V3 p[3] = {P(t[0]), P(t[1]), P(t[2])};
    corner_area[f] = corner_areas(p);
    const V3 face_n = (p[1] - p[0]).cross(p[2] - p[0]);  // twice the area, outward
    for (int j = 0; j < 3; ++j) {
      area[t[j]] += corner_area[f][j];
      const double l2a = (p[next(j)] - p[j]).squaredNorm(), l2b = (p[prev(j)] - p[j]).squaredNorm();
      if (options.normal_weights == NormalWeights::area)
        normal[t[j]] += face_n;
      else if (l2a > 0 && l2b > 0)
        normal[t[j]] += face_n / (l2a * l2b);
    }
  }
  for (std::size_t i = 0; i < nv; ++i) {
    V3 n = normal[i];
    if (options.vertex_normals) {
      const V3 given = to_v3((*options.vertex_normals)[i]);
      if (given.allFinite() && given.squaredNorm() > 0) n = given;
    }
    const double len = n.norm();
    normal[i] = (len > 0 && std::isfinite(len)) ? V3(n / len) : V3::Zero();
  }

  // 3. Per-vertex tangent basis.
  std::vector<V3> bu(nv), bv(nv);
  for (std::size_t i = 0; i < nv; ++i) tangent_basis(normal[i], bu[i], bv[i]);

  // Each triangle's frame: t along e[0], b in the plane, (t, b, face normal) right-handed.
  auto face_frame = [&](const V3 p[3], V3 e[3], V3& t, V3& b) {
    e[0] = p[2] - p[1], e[1] = p[0] - p[2], e[2] = p[1] - p[0];
    t = e[0].normalized();
    b = e[0].cross(e[1]).cross(t).normalized();
  };

  // 4. Per-face second fundamental form, rotated and area-weighted into each corner's vertex.
  std::vector<V3> tensor(nv, V3::Zero());  // (ku, kuv, kv) in (bu, bv)
  std::vector<double> weight(nv, 0);
  std::vector<bool> face_ok(nf, false);
  for (std::size_t f = 0; f < nf; ++f) {
    const Tri& tri = mesh.triangles[f];
    if (repeated_index(tri) || corner_area[f][0] + corner_area[f][1] + corner_area[f][2] <= 0)
      continue;
    const V3 p[3] = {P(tri[0]), P(tri[1]), P(tri[2])};
    V3 e[3], t, b;
    face_frame(p, e, t, b);
    // II (u, v)^T = (dn.t, dn.b) for each edge (u, v) with normal change dn: 6 equations in
    // (ku, kuv, kv), solved through the normal equations.
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    V3 rhs = V3::Zero();
    for (int j = 0; j < 3; ++j) {
      const double u = e[j].dot(t), v = e[j].dot(b);
      const V3 dn = normal[tri[prev(j)]] - normal[tri[next(j)]];
      const double dnu = dn.dot(t), dnv = dn.dot(b);
      A(0, 0) += u * u;
      A(0, 1) += u * v;
      A(2, 2) += v * v;
      rhs += V3(dnu * u, dnu * v + dnv * u, dnv * v);
    }
    A(1, 1) = A(0, 0) + A(2, 2);
    A(1, 2) = A(0, 1);
    A(1, 0) = A(0, 1), A(2, 1) = A(1, 2);
    V3 k;
    if (!ldlt_solve<3>(A, rhs, k)) continue;
    face_ok[f] = true;
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t vj = tri[j];
      tensor[vj] += corner_area[f][j] * change_tensor(k, frame_change(t, b, bu[vj], bv[vj]));
      weight[vj] += corner_area[f][j];
    }
  }

  // 5. Principal curvatures and directions.
  CurvatureField out;
  out.normals.resize(nv), out.area.resize(nv), out.k1.resize(nv), out.k2.resize(nv);
  out.dir1.resize(nv), out.dir2.resize(nv), out.H.resize(nv), out.K.resize(nv);
  out.dcurv.resize(nv), out.shape_index.resize(nv), out.curvedness.resize(nv);
  out.ao.resize(nv), out.boundary.assign(nv, 0);
  std::vector<double> k1(nv), k2(nv);
  std::vector<V3> d1(nv), d2(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const V3 k = weight[i] > 0 ? V3(tensor[i] / weight[i]) : V3::Zero();
    const double ku = k[0], kuv = k[1], kv = k[2];
    double c = 1, s = 0, tt = 0;  // one Jacobi rotation zeroes the off-diagonal
    if (kuv != 0) {
      const double h = 0.5 * (kv - ku) / kuv;
      tt = h < 0 ? 1 / (h - std::sqrt(1 + h * h)) : 1 / (h + std::sqrt(1 + h * h));
      c = 1 / std::sqrt(1 + tt * tt);
      s = tt * c;
    }
    k1[i] = ku - tt * kuv;
    k2[i] = kv + tt * kuv;
    d1[i] = c * bu[i] - s * bv[i];
    if (k1[i] < k2[i]) {
      std::swap(k1[i], k2[i]);
      d1[i] = s * bu[i] + c * bv[i];
    }
    d2[i] = normal[i].cross(d1[i]);
    out.normals[i] = to_f3(normal[i]);
    out.area[i] = float(area[i]);
    out.k1[i] = float(k1[i]), out.k2[i] = float(k2[i]);
    out.dir1[i] = to_f3(d1[i]), out.dir2[i] = to_f3(d2[i]);
    out.H[i] = float((k1[i] + k2[i]) / 2), out.K[i] = float(k1[i] * k2[i]);
    out.shape_index[i] = float(shape_index(k1[i], k2[i]));
    out.curvedness[i] = float(curvedness(k1[i], k2[i]));
    out.ao[i] = float(ambient_occlusion(k1[i], k2[i], double(options.ao_scale)));
  }

  // 6. Curvature derivative: least squares on the per-face differences of the vertex tensors.
  std::vector<Vec4d> dcurv(nv, Vec4d::Zero());
  for (std::size_t f = 0; f < nf; ++f) {
    if (!face_ok[f]) continue;
    const Tri& tri = mesh.triangles[f];
    const V3 p[3] = {P(tri[0]), P(tri[1]), P(tri[2])};
    V3 e[3], t, b;
    face_frame(p, e, t, b);
    // x[j]: vertex j's principal frame, rotated into the face plane, in face coordinates. Its
    // transpose is the face frame, rotated into the vertex's plane, in principal coordinates.
    Eigen::Matrix2d x[3];
    V3 fk[3];  // each vertex's tensor in the face frame
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t vj = tri[j];
      x[j] = frame_change(t, b, d1[vj], d2[vj]);
      fk[j] = change_tensor(V3(k1[vj], 0, k2[vj]), x[j].transpose());
    }
    // dII(u, v) = (a u + b v, b u + c v, c u + d v) for C = (a, b, c, d); the kuv row counts
    // twice (it stands for both off-diagonal entries).
    Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
    Vec4d rhs = Vec4d::Zero();
    for (int j = 0; j < 3; ++j) {
      const double u = e[j].dot(t), v = e[j].dot(b);
      const V3 dk = fk[prev(j)] - fk[next(j)];
      A(0, 0) += u * u;
      A(0, 1) += u * v;
      A(3, 3) += v * v;
      rhs += Vec4d(u * dk[0], v * dk[0] + 2 * u * dk[1], 2 * v * dk[1] + u * dk[2], v * dk[2]);
    }
    A(1, 1) = 2 * A(0, 0) + A(3, 3);
    A(1, 2) = 2 * A(0, 1);
    A(2, 2) = A(0, 0) + 2 * A(3, 3);
    A(2, 3) = A(0, 1);
    A(1, 0) = A(0, 1), A(2, 1) = A(1, 2), A(3, 2) = A(2, 3);
    Vec4d C;
    if (!ldlt_solve<4>(A, rhs, C)) continue;
    for (int j = 0; j < 3; ++j) {
      dcurv[tri[j]] += corner_area[f][j] * change_cubic(C, x[j]);
    }
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec4d d = weight[i] > 0 ? Vec4d(dcurv[i] / weight[i]) : Vec4d::Zero();
    out.dcurv[i] = {float(d[0]), float(d[1]), float(d[2]), float(d[3])};
  }

  // Boundary: vertices of an edge that only one (non-repeated-index) triangle uses.
  out.boundary = boundary_vertices(mesh);
  return out;
}

}  // namespace isocurv::curvature
