#include "core/vec3.h"
#include "features/detail/geodesic_disc.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>

namespace isocurv::features::detail {
namespace {

using V3 = std::array<double, 3>;

using vec3::cross;
using vec3::norm;

/// How much the linear interpolation of a distance over a triangle exceeds the
/// distance itself, on average over the triangle: a distance d from a far
/// source has Hessian (I - g g^T) / d (g its unit gradient), and linear
/// interpolation overestimates a function with Hessian M by sum over edges
/// lambda_i lambda_j e_ij^T M e_ij / 2, whose mean over the triangle is sum
/// over edges e_ij^T M e_ij / 24. Left uncorrected, the disc's rim would be
/// pulled in by that much, an area deficit of about h^2 / (4 r^2) relative (h
/// the edge length): for r of 6 edges already K = 0.6 / r^2 on a plane. Zero
/// near the source, where the distance is no longer smooth.
double interpolation_excess(const double e1[3], const double e2[3],
                            const double d[3]) {
  const double mean = (d[0] + d[1] + d[2]) / 3;
  // Gradient of the interpolant in the triangle's plane: g . e1 = d1 - d0, g .
  // e2 = d2 - d0.
  const double a11 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
  const double a22 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
  const double a12 = e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2];
  const double det = a11 * a22 - a12 * a12;
  if (!(det > 0))
    return 0;
  const double longest2 = std::max({a11, a22, a11 + a22 - 2 * a12});
  if (mean * mean < 4 * longest2)
    return 0; // too close to the source
  const double b1 = d[1] - d[0], b2 = d[2] - d[0];
  const double c1 = (a22 * b1 - a12 * b2) / det,
               c2 = (a11 * b2 - a12 * b1) / det;
  V3 g{c1 * e1[0] + c2 * e2[0], c1 * e1[1] + c2 * e2[1],
       c1 * e1[2] + c2 * e2[2]};
  const double gn = norm(g);
  if (!(gn > 0))
    return 0;
  for (double &x : g)
    x /= gn;
  const double e3[3] = {e2[0] - e1[0], e2[1] - e1[1], e2[2] - e1[2]};
  double sum = 0;
  for (const double *e : {e1, e2, static_cast<const double *>(e3)}) {
    const double along = e[0] * g[0] + e[1] * g[1] + e[2] * g[2];
    sum += e[0] * e[0] + e[1] * e[1] + e[2] * e[2] - along * along;
  }
  return sum / (24 * mean);
}

double distance(const Vec3f &a, const Vec3f &b) {
  const double d0 = double(a[0]) - b[0], d1 = double(a[1]) - b[1],
               d2 = double(a[2]) - b[2];
  return std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

} // namespace

double triangle_update(const Vec3f &a, const Vec3f &b, const Vec3f &c,
                       double da, double db) {
  const double ab = distance(a, b), ac = distance(a, c), bc = distance(b, c);
  const double by_edges = std::min(da + ac, db + bc);
  if (!(ab > 0) || !(ac > 0))
    return by_edges;
  // Plane frame: a at the origin, b at (ab, 0), c at (cx, cy) with cy > 0.
  const double cx = (ac * ac - bc * bc + ab * ab) / (2 * ab);
  const double cy2 = ac * ac - cx * cx;
  if (!(cy2 > 0))
    return by_edges;
  const double cy = std::sqrt(cy2);
  // The virtual source s, below ab, at distances da from a and db from b.
  const double sx = (da * da - db * db + ab * ab) / (2 * ab);
  const double sy2 = da * da - sx * sx;
  if (!(sy2 >= 0))
    return by_edges;
  const double sy = -std::sqrt(sy2);
  // The straight path s -> c must cross ab between a and b.
  const double x_cross = sx + (cx - sx) * (-sy) / (cy - sy);
  if (x_cross < 0 || x_cross > ab)
    return by_edges;
  return std::min(by_edges, std::hypot(cx - sx, cy - sy));
}

double positive_fraction(double f0, double f1, double f2) {
  const int in = (f0 >= 0) + (f1 >= 0) + (f2 >= 0);
  if (in == 3)
    return 1;
  if (in == 0)
    return 0;
  // Rotate so that the lone corner (inside for in == 1, outside for in == 2)
  // comes first.
  const bool lone_inside = in == 1;
  double a = f0, b = f1, c = f2;
  auto lone = [&](double x) { return lone_inside ? x >= 0 : x < 0; };
  if (!lone(a)) {
    if (lone(b))
      std::swap(a, b);
    else
      std::swap(a, c);
  }
  // The corner triangle at the lone corner, cut where the function crosses zero
  // on its edges.
  const double t_ab = a / (a - b), t_ac = a / (a - c);
  const double corner = t_ab * t_ac;
  return lone_inside ? corner : 1 - corner;
}

GeodesicDisc geodesic_disc(const Mesh &mesh, const MeshGraph &graph,
                           std::uint32_t v, double r, double max_edge,
                           GeodesicScratch &s) {
  const std::size_t n = mesh.vertex_count();
  if (s.stamp.size() != n) {
    s.dist.assign(n, 0);
    s.stamp.assign(n, 0);
    s.done.assign(n, 0);
    s.mark = 0;
  }
  if (++s.mark == 0) { // wrapped: clear the stamps
    std::fill(s.stamp.begin(), s.stamp.end(), 0);
    s.mark = 1;
  }
  const std::uint32_t mark = s.mark;
  auto known = [&](std::uint32_t w) { return s.stamp[w] == mark; };
  auto dist = [&](std::uint32_t w) {
    return known(w) ? s.dist[w] : std::numeric_limits<double>::infinity();
  };
  using Entry = std::pair<double, std::uint32_t>;
  auto later = std::greater<Entry>();
  s.heap.clear();
  s.touched.clear();
  auto offer = [&](std::uint32_t w, double d) {
    if (!known(w)) {
      s.stamp[w] = mark;
      s.done[w] = 0;
      s.dist[w] = d;
      s.touched.push_back(w);
    } else if (s.done[w] || d >= s.dist[w]) {
      return;
    } else {
      s.dist[w] = d;
    }
    s.heap.push_back({d, w});
    std::push_heap(s.heap.begin(), s.heap.end(), later);
  };

  GeodesicDisc out;
  const double limit = r + max_edge;
  offer(v, 0);
  while (!s.heap.empty()) {
    std::pop_heap(s.heap.begin(), s.heap.end(), later);
    const auto [d, u] = s.heap.back();
    s.heap.pop_back();
    if (s.done[u] || d > s.dist[u])
      continue; // stale entry
    if (d > limit)
      break;
    s.done[u] = 1;
    if (d <= r && graph.on_boundary[u])
      out.touches_boundary = true;
    for (std::uint32_t k = graph.vt_start[u]; k < graph.vt_start[u + 1]; ++k) {
      const Tri &t = mesh.triangles[graph.vt[k]];
      const int c = t[0] == u ? 0 : t[1] == u ? 1 : 2;
      const std::uint32_t p = t[(c + 1) % 3], q = t[(c + 2) % 3];
      const Vec3f &xu = mesh.positions[u], &xp = mesh.positions[p],
                  &xq = mesh.positions[q];
      // Each other corner from u along the edge, or across the triangle when
      // its partner is final.
      offer(p, known(q) && s.done[q] ? triangle_update(xu, xq, xp, d, s.dist[q])
                                     : d + distance(xu, xp));
      offer(q, known(p) && s.done[p] ? triangle_update(xu, xp, xq, d, s.dist[p])
                                     : d + distance(xu, xq));
    }
  }

  // Area where the piecewise linear distance is <= r, over the triangles of the
  // reached vertices (each triangle counted once: at its corner of smallest
  // index among the reached ones).
  for (std::uint32_t u : s.touched) {
    if (!(s.dist[u] <= r))
      continue;
    for (std::uint32_t k = graph.vt_start[u]; k < graph.vt_start[u + 1]; ++k) {
      const Tri &t = mesh.triangles[graph.vt[k]];
      bool first = true;
      for (int c = 0; c < 3; ++c)
        if (t[c] < u && dist(t[c]) <= r)
          first = false;
      if (!first)
        continue;
      const Vec3f *x[3] = {&mesh.positions[t[0]], &mesh.positions[t[1]],
                           &mesh.positions[t[2]]};
      const V3 e1 = vec3::sub(vec3::to_double(*x[1]), vec3::to_double(*x[0]));
      const V3 e2 = vec3::sub(vec3::to_double(*x[2]), vec3::to_double(*x[0]));
      const double area = 0.5 * norm(cross(e1, e2));
      // Unreached corners lie beyond the march's limit: far outside.
      double d[3];
      bool reached = true;
      for (int c = 0; c < 3; ++c) {
        reached = reached && known(t[c]);
        d[c] = known(t[c]) ? s.dist[t[c]] : 2 * limit;
      }
      const double shift = reached ? interpolation_excess(e1.data(), e2.data(), d) : 0;
      out.area += area * positive_fraction(r - d[0] + shift, r - d[1] + shift,
                                           r - d[2] + shift);
    }
  }
  return out;
}

} // namespace isocurv::features::detail
