#include "measure/object_measures.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/mesh_measures.h"
#include "core/union_find.h"
#include "core/vec3.h"

namespace isocurv::measure {
namespace {

constexpr double kTwoPi = 6.283185307179586;

bool usable(const Tri& t, std::size_t nv) {
  return t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

using V3 = std::array<double, 3>;

using vec3::sub;
using vec3::dot;
using vec3::cross;
using vec3::to_double;

/// The unit normal of a field normal, or zero when it is missing, not finite or not near unit.
V3 unit_normal(const Vec3f& n) {
  const V3 v = to_double(n);
  const double len = std::sqrt(dot(v, v));
  if (!(len > 0.5 && len < 1.5)) return {0, 0, 0};
  return {v[0] / len, v[1] / len, v[2] / len};
}

/// The edge curve x(t) = x0 (1 - t) + x1 t - c t (1 - t) of the quadratic patch (Nagata 2005):
/// the c that makes the curve's tangents orthogonal to the unit normals n0, n1 (exact on a
/// sphere). Zero where a normal is missing or the normals are nearly opposed; at most
/// kMaxBulge |x1 - x0| long (a noisy normal cannot blow an edge up).
constexpr double kMaxBulge = 0.5;
V3 edge_coefficient(const V3& x0, const V3& x1, const V3& n0, const V3& n1) {
  if (dot(n0, n0) == 0 || dot(n1, n1) == 0) return {0, 0, 0};
  const V3 d = sub(x1, x0);
  const V3 sum = {n0[0] + n1[0], n0[1] + n1[1], n0[2] + n1[2]};
  const double len = std::sqrt(dot(sum, sum));
  const double s2 = 0.5 * (1 + dot(n0, n1));  // cos^2 of half the angle between the normals
  if (!(s2 > 0.01) || !(len > 0)) return {0, 0, 0};
  const double k = dot(sub(n0, n1), d) / (2 * std::sqrt(s2) * len);
  V3 c = {k * sum[0], k * sum[1], k * sum[2]};
  const double cl = std::sqrt(dot(c, c)), limit = kMaxBulge * std::sqrt(dot(d, d));
  if (cl > limit) c = {c[0] * limit / cl, c[1] * limit / cl, c[2] * limit / cl};
  return c;
}

/// Dunavant's 6-point rule on the triangle (degree 4: exact for the patch's volume integrand,
/// a polynomial of degree 4): barycentric points and weights summing to 1.
constexpr double kA = 0.445948490915965, kB = 0.091576213509771;
constexpr double kWa = 0.223381589678011, kWb = 0.109951743655322;
constexpr double kRule[6][4] = {{kA, kA, 1 - 2 * kA, kWa}, {kA, 1 - 2 * kA, kA, kWa},
                                {1 - 2 * kA, kA, kA, kWa}, {kB, kB, 1 - 2 * kB, kWb},
                                {kB, 1 - 2 * kB, kB, kWb}, {1 - 2 * kB, kB, kB, kWb}};

/// Where the interpolated normal is shorter than this (the vertex normals disagree wildly), the
/// area element is not projected on it.
constexpr double kMinNormalSum = 0.5;

/// The integrals over one triangle's patch.
struct PatchIntegrals {
  double area = 0, volume = 0, H = 0, K = 0;
};

/// The quadratic patch x(b) = sum b_i x_i - sum over the edges (i, j) of b_i b_j c_ij over the
/// triangle x0 x1 x2 (b the barycentric coordinates; c_ij from edge_coefficient, zero without
/// normals: the flat triangle), integrated by kRule: area |(x_u x x_v).nbar| (nbar the unit
/// interpolated normal; |x_u x x_v| where it is not defined), volume
/// (x - origin).(x_u x x_v) / 3, and the linear interpolations of h and k times the area.
PatchIntegrals integrate_patch(const V3 x[3], const V3 n[3], const double h[3], const double k[3],
                               const V3& origin) {
  const V3 c01 = edge_coefficient(x[0], x[1], n[0], n[1]);
  const V3 c12 = edge_coefficient(x[1], x[2], n[1], n[2]);
  const V3 c20 = edge_coefficient(x[2], x[0], n[2], n[0]);
  const V3 e1 = sub(x[1], x[0]), e2 = sub(x[2], x[0]), r0 = sub(x[0], origin);
  PatchIntegrals out;
  for (const auto& q : kRule) {
    const double b0 = q[0], u = q[1], v = q[2], w = 0.5 * q[3];  // reference triangle area 1/2
    // b0 = 1 - u - v, b1 = u, b2 = v; derivatives of b0 b1, b1 b2, b2 b0 along u and v.
    const double a01u = b0 - u, a01v = -u, a12u = v, a12v = u, a20u = -v, a20v = b0 - v;
    V3 xu, xv, p;
    for (int i = 0; i < 3; ++i) {
      xu[i] = e1[i] - a01u * c01[i] - a12u * c12[i] - a20u * c20[i];
      xv[i] = e2[i] - a01v * c01[i] - a12v * c12[i] - a20v * c20[i];
      p[i] = r0[i] + u * e1[i] + v * e2[i] - b0 * u * c01[i] - u * v * c12[i] - v * b0 * c20[i];
    }
    const V3 nrm = cross(xu, xv);
    // The area element projected on the field's normal there (interpolated): noise tilts the
    // marching-cubes triangles of a noisy scan every which way, and their own area counts that
    // roughness as surface (+0.5% on the CT-like solids, bench_measure); its projection on the
    // smooth surface's tangent plane does not. Exact where the patch follows the normals.
    double da = std::sqrt(dot(nrm, nrm)) * w;
    V3 nb;
    for (int i = 0; i < 3; ++i) nb[i] = b0 * n[0][i] + u * n[1][i] + v * n[2][i];
    const double nl = std::sqrt(dot(nb, nb));
    if (nl > kMinNormalSum) da = std::abs(dot(nrm, nb)) / nl * w;
    out.area += da;
    out.volume += dot(p, nrm) * w / 3;
    out.H += (b0 * h[0] + u * h[1] + v * h[2]) * da;
    out.K += (b0 * k[0] + u * k[1] + v * k[2]) * da;
  }
  return out;
}

}  // namespace

double ObjectMeasures::gauss_bonnet_gap() const {
  if (!closed) return std::numeric_limits<double>::quiet_NaN();
  return (integral_K - kTwoPi * double(euler)) / (kTwoPi * std::max(1.0, std::abs(double(euler))));
}

double ObjectMeasures::curvature_genus() const {
  if (!closed) return std::numeric_limits<double>::quiet_NaN();
  return 1 - integral_K / (2 * kTwoPi);
}

bool ObjectMeasures::has_fine_handles() const {
  if (!closed || !resolved) return false;
  const double missing = double(genus()) - curvature_genus();
  return missing > kFineHandles && missing > 0.1 * double(genus());
}

std::vector<ObjectMeasures> object_measures(const Mesh& mesh, const curvature::CurvatureField& field) {
  const std::size_t nv = mesh.positions.size();
  if (field.H.size() != nv || field.K.size() != nv)
    throw Error("measure: the curvature field has " + std::to_string(field.H.size()) + " H and " +
                std::to_string(field.K.size()) + " K values for " + std::to_string(nv) + " vertices");
  // The curved path (object_measures.h) where the field has normals.
  const bool curved = field.normals.size() == nv;
  const bool moved = curved && field.surface_points.size() == nv;
  UnionFind uf(nv);
  std::vector<std::uint64_t> edges;  // (lo, hi) packed, one per triangle side
  edges.reserve(3 * mesh.triangles.size());
  std::vector<double> third_area;  // a third of the adjacent triangles' areas (no Area array)
  const bool have_area = field.area.size() == nv;
  if (!have_area) third_area.assign(nv, 0.0);
  for (const Tri& t : mesh.triangles) {
    if (!usable(t, nv)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      uf.unite(a, b);
      edges.push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
    if (!have_area) {
      const auto n = triangle_area_vector(mesh, t);
      const double a = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 3;
      for (std::uint32_t i : t) third_area[i] += a;
    }
  }
  // The per-vertex smoothing scale, when the field has one (the volume estimator's).
  const std::vector<float>* scales = field.find_extra("Scale");
  if (scales && scales->size() != nv) scales = nullptr;
  // The positions integrated over: the field's surface points where it has them (finite).
  const auto position = [&](std::uint32_t i) -> const Vec3f& {
    if (moved) {
      const Vec3f& p = field.surface_points[i];
      if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) return p;
    }
    return mesh.positions[i];
  };
  // Components in order of their lowest vertex (the union-find root), vertices that some usable
  // triangle uses.
  std::vector<std::uint32_t> index(nv, ~0u);
  std::vector<ObjectMeasures> out;
  std::vector<PatchIntegrals> on_vertices;  // each component over the mesh's own vertices (moved)
  std::vector<char> used(nv, 0);
  for (const Tri& t : mesh.triangles)
    if (usable(t, nv))
      for (std::uint32_t i : t) used[i] = 1;
  for (std::uint32_t i = 0; i < nv; ++i) {
    if (!used[i]) continue;
    const std::uint32_t root = uf.find(i);
    if (index[root] == ~0u) {
      index[root] = std::uint32_t(out.size());
      ObjectMeasures m;
      m.first_vertex = i;
      m.box = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
      out.push_back(m);
      on_vertices.push_back({});
    }
    ObjectMeasures& m = out[index[root]];
    ++m.vertices;
    const double a = have_area ? double(field.area[i]) : third_area[i];
    const bool flagged = field.unreliable.size() == nv && field.unreliable[i];
    m.unmeasured += flagged;
    if (!flagged && std::isfinite(field.H[i]) && std::isfinite(field.K[i])) {
      if (!curved) m.integral_H += double(field.H[i]) * a;
      if (!moved) m.integral_K += double(field.K[i]) * a;  // see ObjectMeasures::integral_K
    }
    if (scales) m.scale = std::max(m.scale, double((*scales)[i]));
    for (int c = 0; c < 3; ++c) {
      m.box[2 * c] = std::min(m.box[2 * c], double(mesh.positions[i][c]));
      m.box[2 * c + 1] = std::max(m.box[2 * c + 1], double(mesh.positions[i][c]));
    }
  }
  // Each vertex's component, so that the patches can be integrated in parallel (find() compresses
  // paths: not from several threads).
  std::vector<std::uint32_t> component(nv, ~0u);
  for (std::uint32_t i = 0; i < nv; ++i)
    if (used[i]) component[i] = index[uf.find(i)];
  // The patches' integrals, one per triangle (over the surface points and, when they are used,
  // over the vertices), computed in parallel and summed below in triangle order: deterministic.
  std::vector<PatchIntegrals> patch, own;
  if (curved) {
    patch.resize(mesh.triangles.size());
    if (moved) own.resize(mesh.triangles.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.triangles.size(), 4096), [&](const auto& r) {
      for (std::size_t ti = r.begin(); ti != r.end(); ++ti) {
        const Tri& t = mesh.triangles[ti];
        if (!usable(t, nv)) continue;
        const std::uint32_t first = out[component[t[0]]].first_vertex;
        V3 x[3], n[3];
        double h[3], k[3];
        for (int c = 0; c < 3; ++c) {
          const std::uint32_t i = t[c];
          x[c] = to_double(position(i));
          n[c] = unit_normal(field.normals[i]);
          const bool measured = !(field.unreliable.size() == nv && field.unreliable[i]) &&
                                std::isfinite(field.H[i]) && std::isfinite(field.K[i]);
          h[c] = measured ? double(field.H[i]) : 0.0;
          k[c] = measured ? double(field.K[i]) : 0.0;
        }
        patch[ti] = integrate_patch(x, n, h, k, to_double(position(first)));
        if (moved) {
          for (int c = 0; c < 3; ++c) x[c] = to_double(mesh.positions[t[c]]);
          own[ti] = integrate_patch(x, n, h, k, to_double(mesh.positions[first]));
        }
      }
    });
  }
  for (std::size_t ti = 0; ti < mesh.triangles.size(); ++ti) {
    const Tri& t = mesh.triangles[ti];
    if (!usable(t, nv)) continue;
    ObjectMeasures& m = out[component[t[0]]];
    ++m.triangles;
    const auto n = triangle_area_vector(mesh, t);
    const double flat = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    m.mesh_area += flat;
    if (!curved) {
      m.area += flat;
      m.volume += signed_volume_term(mesh, t, mesh.positions[m.first_vertex]);
      continue;
    }
    const PatchIntegrals& p = patch[ti];
    m.area += p.area;
    m.volume += p.volume;
    m.integral_H += p.H;
    if (moved) {
      m.integral_K += p.K;
      const PatchIntegrals& q = own[ti];
      PatchIntegrals& v = on_vertices[component[t[0]]];
      v.area += q.area;
      v.volume += q.volume;
      v.H += q.H;
      v.K += q.K;
    }
  }
  tbb::parallel_sort(edges.begin(), edges.end());  // keys are distinct or equal: deterministic
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    ObjectMeasures& m = out[component[std::uint32_t(edges[i] >> 32)]];
    ++m.edges;
    if (j - i == 1) ++m.boundary_edges;
    i = j;
  }
  for (std::size_t c = 0; c < out.size(); ++c) {
    ObjectMeasures& m = out[c];
    m.closed = m.boundary_edges == 0;
    m.euler = (long long)m.vertices - (long long)m.edges + (long long)m.triangles;
    const double shortest = std::min({m.box[1] - m.box[0], m.box[3] - m.box[2], m.box[5] - m.box[4]});
    m.resolved = !(shortest < kResolvedExtent * m.scale);
    if (!moved) continue;
    // A component below the estimator's scale (a speck, a sheet a voxel thick) has no smoothed
    // isosurface of its own to move to: its surface points scatter, and can turn it inside out.
    // Where they change its area, or a closed one's volume, by more than kMaxSurfaceChange, it
    // is measured over the mesh's own vertices instead.
    const PatchIntegrals& v = on_vertices[c];
    auto off = [](double moved_value, double own) {
      return !(std::abs(moved_value - own) <= kMaxSurfaceChange * std::abs(own));
    };
    if (off(m.area, v.area) || (m.closed && off(m.volume, v.volume))) {
      m.area = v.area;
      m.volume = v.volume;
      m.integral_H = v.H;
      m.integral_K = v.K;
      m.on_vertices = true;
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ObjectMeasures& a, const ObjectMeasures& b) { return a.area > b.area; });
  return out;
}

long long genus_sum(const std::vector<ObjectMeasures>& objects) {
  long long genus = 0;
  for (const ObjectMeasures& m : objects) genus = (genus < 0 || !m.closed) ? -1 : genus + m.genus();
  return genus;
}

ObjectMeasures total(const std::vector<ObjectMeasures>& objects) {
  ObjectMeasures t;
  t.closed = true;
  t.box = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (const ObjectMeasures& m : objects) {
    t.vertices += m.vertices, t.triangles += m.triangles, t.edges += m.edges;
    t.boundary_edges += m.boundary_edges;
    t.closed = t.closed && m.closed;
    t.area += m.area, t.volume += m.volume, t.mesh_area += m.mesh_area;
    t.scale = std::max(t.scale, m.scale);
    t.resolved = t.resolved && m.resolved;
    t.integral_H += m.integral_H, t.integral_K += m.integral_K;
    t.euler += m.euler;
    t.unmeasured += m.unmeasured;
    t.on_vertices = t.on_vertices || m.on_vertices;
    for (int c = 0; c < 3; ++c) {
      t.box[2 * c] = std::min(t.box[2 * c], m.box[2 * c]);
      t.box[2 * c + 1] = std::max(t.box[2 * c + 1], m.box[2 * c + 1]);
    }
  }
  return t;
}

}  // namespace isocurv::measure
