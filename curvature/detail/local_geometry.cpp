#include "curvature/detail/local_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "curvature/derived.h"
#include "curvature/field_stats.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"

namespace isocurv::curvature::detail {
namespace {

int next(int j) { return j == 2 ? 0 : j + 1; }
int prev(int j) { return j == 0 ? 2 : j - 1; }

// Meyer et al.'s mixed corner areas of the triangle p (see the Rusinkiewicz reference).
std::array<double, 3> corner_areas(const V3 p[3]) {
  const V3 e[3] = {p[2] - p[1], p[0] - p[2], p[1] - p[0]};  // e[j] is opposite corner j
  const double area = 0.5 * e[0].cross(e[1]).norm();
  if (!(area > 0)) return {0, 0, 0};
  const double l2[3] = {e[0].squaredNorm(), e[1].squaredNorm(), e[2].squaredNorm()};
  for (int j = 0; j < 3; ++j)
    if (l2[j] > l2[next(j)] + l2[prev(j)]) {  // obtuse at corner j
      std::array<double, 3> a{area / 4, area / 4, area / 4};
      a[j] = area / 2;
      return a;
    }
  double w[3];
  for (int j = 0; j < 3; ++j) w[j] = l2[j] * (l2[next(j)] + l2[prev(j)] - l2[j]);
  const double sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) return {area / 3, area / 3, area / 3};
  const double scale = area / (2 * sum);
  return {scale * (w[1] + w[2]), scale * (w[2] + w[0]), scale * (w[0] + w[1])};
}

}  // namespace

std::vector<V3> vertex_normals(const Mesh& mesh, const Options& options, NormalSource source) {
  const std::size_t nv = mesh.positions.size();
  std::vector<V3> normal(nv, V3::Zero());
  for (const Tri& t : mesh.triangles) {
    if (repeated_index(t)) continue;
    const V3 p[3] = {to_v3(mesh.positions[t[0]]), to_v3(mesh.positions[t[1]]),
                     to_v3(mesh.positions[t[2]])};
    const V3 face_n = (p[1] - p[0]).cross(p[2] - p[0]);  // twice the area, outward
    const double len = face_n.norm();
    for (int j = 0; j < 3; ++j) {
      if (source == NormalSource::uniform) {
        if (len > 0) normal[t[j]] += face_n / len;
      } else if (options.normal_weights == NormalWeights::area) {
        normal[t[j]] += face_n;
      } else {
        const double l2a = (p[next(j)] - p[j]).squaredNorm();
        const double l2b = (p[prev(j)] - p[j]).squaredNorm();
        if (l2a > 0 && l2b > 0) normal[t[j]] += face_n / (l2a * l2b);
      }
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
  return normal;
}

Neighbours vertex_neighbours(const Mesh& mesh) {
  VertexCorners corners;
  build_vertex_corners(mesh, corners);
  return vertex_neighbours(mesh, corners);
}

Neighbours vertex_neighbours(const Mesh& mesh, const VertexCorners& corners) {
  const std::size_t nv = mesh.positions.size();
  Neighbours n;
  n.offsets.assign(nv + 1, 0);
  n.ids.reserve(corners.corners.size() + nv);  // closed fans: as many neighbours as corners
  std::vector<std::uint32_t> ring;
  for (std::size_t v = 0; v < nv; ++v) {
    ring.clear();
    for (std::uint32_t k = corners.offsets[v]; k < corners.offsets[v + 1]; ++k) {
      const std::uint32_t c = corners.corners[k], f = c / 3, j = c % 3;
      const Tri& t = mesh.triangles[f];
      ring.push_back(t[next(int(j))]);
      ring.push_back(t[prev(int(j))]);
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    n.ids.insert(n.ids.end(), ring.begin(), ring.end());
    n.offsets[v + 1] = std::uint32_t(n.ids.size());
  }
  return n;
}

std::vector<double> mixed_vertex_areas(const Mesh& mesh) {
  std::vector<double> area(mesh.positions.size(), 0);
  for (const Tri& t : mesh.triangles) {
    if (repeated_index(t)) continue;
    const V3 p[3] = {to_v3(mesh.positions[t[0]]), to_v3(mesh.positions[t[1]]),
                     to_v3(mesh.positions[t[2]])};
    const std::array<double, 3> a = corner_areas(p);
    for (int j = 0; j < 3; ++j) area[t[j]] += a[j];
  }
  return area;
}

std::vector<std::uint8_t> boundary_flags(const Mesh& mesh) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const Tri& t : mesh.triangles)
    if (!repeated_index(t))
      for (int j = 0; j < 3; ++j) edges.push_back(std::minmax(t[j], t[next(j)]));
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint8_t> flag(mesh.positions.size(), 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) flag[edges[i].first] = flag[edges[i].second] = 1;
    i = j;
  }
  return flag;
}

void tangent_basis(const V3& n, V3& u, V3& v) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  u = V3(1 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  v = V3(b, sign + n.y() * n.y() * a, -n.y());
}

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

Principal diagonalise(double ku, double kuv, double kv, const V3& u, const V3& v, const V3& n) {
  double c = 1, s = 0, tt = 0;  // one Jacobi rotation zeroes the off-diagonal
  if (kuv != 0) {
    const double h = 0.5 * (kv - ku) / kuv;
    tt = h < 0 ? 1 / (h - std::sqrt(1 + h * h)) : 1 / (h + std::sqrt(1 + h * h));
    c = 1 / std::sqrt(1 + tt * tt);
    s = tt * c;
  }
  Principal p;
  p.k1 = ku - tt * kuv;
  p.k2 = kv + tt * kuv;
  p.d1 = c * u - s * v;
  if (p.k1 < p.k2) {
    std::swap(p.k1, p.k2);
    p.d1 = s * u + c * v;
  }
  p.d2 = n.cross(p.d1);
  return p;
}

CurvatureField allocate_field(const Mesh& mesh, bool with_directions) {
  const std::size_t nv = mesh.positions.size();
  CurvatureField out;
  out.normals.resize(nv), out.k1.resize(nv), out.k2.resize(nv), out.H.resize(nv);
  out.K.resize(nv), out.shape_index.resize(nv), out.curvedness.resize(nv), out.ao.resize(nv);
  if (with_directions) out.dir1.resize(nv), out.dir2.resize(nv);
  out.unreliable.assign(nv, 0);
  const std::vector<double> area = mixed_vertex_areas(mesh);
  out.area.assign(area.begin(), area.end());
  out.boundary = boundary_flags(mesh);
  return out;
}

void set_vertex(CurvatureField& out, std::size_t i, const V3& normal, double k1, double k2,
                float ao_scale) {
  out.normals[i] = to_f3(normal);
  out.k1[i] = float(k1), out.k2[i] = float(k2);
  out.H[i] = float((k1 + k2) / 2), out.K[i] = float(k1 * k2);
  out.shape_index[i] = float(shape_index(k1, k2));
  out.curvedness[i] = float(curvedness(k1, k2));
  out.ao[i] = float(ambient_occlusion(k1, k2, double(ao_scale)));
}

CurvatureField fit_each_vertex(const Mesh& mesh, const Options& options,
                               std::size_t min_neighbours, const VertexFit& fit) {
  check_input(mesh, options);
  const std::size_t nv = mesh.positions.size();
  const std::vector<V3> normal = vertex_normals(mesh, options);
  const Neighbours nb = vertex_neighbours(mesh);
  CurvatureField out = allocate_field(mesh, /*with_directions=*/true);
  VertexRing ring;
  ring.plausible = implausible_above(mesh, options.piece);
  for (std::size_t i = 0; i < nv; ++i) {
    ring.p = to_v3(mesh.positions[i]);
    ring.n = normal[i];
    tangent_basis(ring.n, ring.u, ring.v);
    ring.q.clear(), ring.nq.clear();
    for (std::uint32_t k = nb.offsets[i]; k < nb.offsets[i + 1]; ++k) {
      ring.q.push_back(to_v3(mesh.positions[nb.ids[k]]));
      ring.nq.push_back(normal[nb.ids[k]]);
    }
    V3 t = V3::Zero();
    const bool ok = ring.n.squaredNorm() > 0 && ring.q.size() >= min_neighbours &&
                    fit(ring, t) && t.allFinite();
    Principal pr;
    if (ok) {
      pr = diagonalise(t[0], t[1], t[2], ring.u, ring.v, ring.n);
    } else {
      pr.d1 = ring.u, pr.d2 = ring.v;
      out.unreliable[i] = 1;
    }
    set_vertex(out, i, ring.n, pr.k1, pr.k2, options.ao_scale);
    out.dir1[i] = to_f3(pr.d1), out.dir2[i] = to_f3(pr.d2);
  }
  return out;
}

bool least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (A.rows() < A.cols()) return false;
  Eigen::VectorXd scale = A.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c)
    if (!(scale[c] > 0)) return false;
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  qr.setThreshold(1e-8);
  if (qr.rank() < A.cols()) return false;
  x = qr.solve(b).cwiseQuotient(scale);
  return x.allFinite();
}

}  // namespace isocurv::curvature::detail
