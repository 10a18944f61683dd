#include "lines/reference.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/vec3.h"
#include "curvature/vertex_corners.h"

namespace isocurv::lines {
namespace {

using V3 = std::array<double, 3>;

using vec3::to_double;
Vec3f to_f3(const V3 &a) { return {float(a[0]), float(a[1]), float(a[2])}; }
using vec3::dot;
using vec3::sub;
using vec3::add;
using vec3::scale;
using vec3::cross;
double lerp(double a, double b, double t) { return a + t * (b - a); }
double clamp01(double x) { return std::min(1.0, std::max(0.0, x)); }

/// The per-vertex, per-view quantities of the spec.
struct VertexView {
  double ndotv = 0, kr = 0, num = 0;
};

VertexView vertex_view(const Mesh &mesh, const curvature::CurvatureField &f,
                       const Camera &camera, std::size_t i, bool with_dcurv) {
  const V3 p = to_double(mesh.positions[i]);
  const V3 v = camera.view_vector({p[0], p[1], p[2]});
  VertexView q;
  q.ndotv = dot(to_double(f.normals[i]), v);
  if (f.dir1.empty()) return q;  // contours alone, from a field without directions
  const double u = dot(v, to_double(f.dir1[i])), w = dot(v, to_double(f.dir2[i]));
  const double u2 = u * u, w2 = w * w, sin2 = u2 + w2;
  const double k1 = f.k1[i], k2 = f.k2[i];
  q.kr = k1 * u2 + k2 * w2;
  if (with_dcurv && sin2 > 0) {
    const auto &C = f.dcurv[i];
    const double tau = (k2 - k1) * u * w / sin2;
    q.num = (u2 * (u * C[0] + 3 * w * C[1]) + w2 * (3 * u * C[2] + w * C[3])) /
                sin2 -
            2 * q.ndotv * tau * tau;
  }
  return q;
}

/// Where a face's zero set crosses one of its edges.
struct Crossing {
  std::uint32_t lo = 0, hi = 0; // the edge's vertices, lo < hi
  double t = 0;                 // from lo towards hi
};

/// The two edge crossings of the zero set of per-corner values f over face `v`
/// (0 when the values share a sign). Edges in the order (0,1), (1,2), (2,0).
int face_crossings(const Tri &v, const double f[3], Crossing out[2]) {
  int n = 0;
  for (int j = 0; j < 3; ++j) {
    const int k = (j + 1) % 3;
    if ((f[j] > 0) == (f[k] > 0))
      continue;
    const bool j_lo = v[j] < v[k];
    const double f_lo = j_lo ? f[j] : f[k], f_hi = j_lo ? f[k] : f[j];
    double t = f_lo / (f_lo - f_hi);
    if (t < kVertexSnap)
      t = 0; // on the vertex, for rounding-proof joins (segments.h)
    if (t > 1 - kVertexSnap)
      t = 1;
    if (n < 2)
      out[n] = {j_lo ? v[j] : v[k], j_lo ? v[k] : v[j], t};
    ++n;
  }
  return n == 2 ? 2 : 0;
}

/// A per-vertex quantity interpolated at a crossing.
template <class Get> double at(const Crossing &c, Get get) {
  return lerp(get(c.lo), get(c.hi), c.t);
}

/// The key of the point: the edge's, or the vertex's (edge_key(v, v)) when it
/// lies on one.
std::uint64_t key_of(const Crossing &c) {
  return c.t == 0   ? edge_key(c.lo, c.lo)
         : c.t == 1 ? edge_key(c.hi, c.hi)
                    : edge_key(c.lo, c.hi);
}

V3 point_at(const Mesh &mesh, const Crossing &c) {
  const V3 a = to_double(mesh.positions[c.lo]), b = to_double(mesh.positions[c.hi]);
  return add(a, scale(sub(b, a), c.t));
}

/// Clips [s0, s1] to where g0 + s (g1 - g0) > 0; false when nothing is left.
bool clip_positive(double g0, double g1, double &s0, double &s1) {
  if (g0 > 0 && g1 > 0)
    return true;
  if (g0 <= 0 && g1 <= 0)
    return false;
  const double s = g0 / (g0 - g1);
  if (g0 > 0)
    s1 = std::min(s1, s);
  else
    s0 = std::max(s0, s);
  return s0 < s1;
}

} // namespace

Segments extract_reference(const Mesh &mesh,
                           const curvature::CurvatureField &field,
                           const Camera &camera, const Options &options) {
  check_input(mesh, field, options);
  const Thresholds th = resolve_thresholds(field, options);
  const LineSelection &sel = options.lines;
  const std::size_t nv = mesh.vertex_count();
  std::vector<VertexView> view(sel.view_dependent() ? nv : 0);
  for (std::size_t i = 0; i < view.size(); ++i)
    view[i] = vertex_view(mesh, field, camera, i, sel.suggestive);

  // Suggestive contours: kr and num averaged over 1-rings
  // (Options::smoothing_steps).
  if (sel.suggestive && options.smoothing_steps > 0) {
    curvature::VertexCorners vc;
    curvature::build_vertex_corners(mesh, vc);
    std::vector<VertexView> next(nv);
    for (int step = 0; step < options.smoothing_steps; ++step) {
      for (std::size_t i = 0; i < nv; ++i) {
        double kr = view[i].kr, num = view[i].num, w = 1;
        for (std::uint32_t k = vc.offsets[i]; k < vc.offsets[i + 1]; ++k) {
          const Tri &t = mesh.triangles[vc.corners[k] / 3];
          const std::uint32_t j = vc.corners[k] % 3, a = t[(j + 1) % 3],
                              b = t[(j + 2) % 3];
          kr += view[a].kr + view[b].kr;
          num += view[a].num + view[b].num;
          w += 2;
        }
        next[i] = {view[i].ndotv, kr / w, num / w};
      }
      view.swap(next);
    }
  }

  Segments out;
  for (std::size_t fi = 0; fi < mesh.triangles.size(); ++fi) {
    const Tri &v = mesh.triangles[fi];
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
      continue;
    const V3 p[3] = {to_double(mesh.positions[v[0]]), to_double(mesh.positions[v[1]]),
                     to_double(mesh.positions[v[2]])};
    const V3 normal2 =
        cross(sub(p[1], p[0]), sub(p[2], p[0])); // twice the area
    const double area2 = std::sqrt(dot(normal2, normal2));
    if (!(area2 > 0) || !std::isfinite(area2))
      continue;
    bool finite = true;
    for (int j = 0; j < 3; ++j) {
      const std::uint32_t i = v[j];
      finite =
          finite && std::isfinite(field.k1[i]) && std::isfinite(field.k2[i]);
      for (int c = 0; c < 3; ++c)
        finite = finite && std::isfinite(field.normals[i][c]);
      if (!field.dir1.empty())
        for (int c = 0; c < 3; ++c)
          finite = finite && std::isfinite(field.dir1[i][c]) &&
                   std::isfinite(field.dir2[i][c]);
      if (sel.needs_dcurv())
        for (float d : field.dcurv[i])
          finite = finite && std::isfinite(d);
      if (!view.empty())
        finite = finite && std::isfinite(view[i].ndotv) &&
                 std::isfinite(view[i].kr) && std::isfinite(view[i].num);
    }
    if (!finite)
      continue;
    const auto face = std::uint32_t(fi);
    auto emit = [&](LineType type, const V3 &a, const V3 &b, std::uint64_t ea,
                    std::uint64_t eb, double strength) {
      if (to_f3(a) == to_f3(b))
        return; // both crossings at one vertex
      out.push_back({to_f3(a), to_f3(b), ea, eb, float(strength), face, type});
    };
    Crossing c[2];

    if (sel.contours) {
      const double f[3] = {view[v[0]].ndotv, view[v[1]].ndotv,
                           view[v[2]].ndotv};
      if (face_crossings(v, f, c))
        emit(LineType::contour, point_at(mesh, c[0]), point_at(mesh, c[1]),
             key_of(c[0]), key_of(c[1]), 1);
    }

    if (sel.suggestive) {
      const double f[3] = {view[v[0]].kr, view[v[1]].kr, view[v[2]].kr};
      if (face_crossings(v, f, c)) {
        double num[2], den[2];
        for (int e = 0; e < 2; ++e) {
          num[e] = at(c[e], [&](std::uint32_t i) { return view[i].num; });
          den[e] = at(c[e], [&](std::uint32_t i) { return view[i].ndotv; });
        }
        double s0 = 0, s1 = 1;
        const bool keep =
            clip_positive(num[0] - th.suggestive * den[0],
                          num[1] - th.suggestive * den[1], s0, s1) &&
            clip_positive(den[0], den[1], s0, s1) &&
            clip_positive(th.cos_angle - den[0], th.cos_angle - den[1], s0, s1);
        if (keep) {
          const V3 a = point_at(mesh, c[0]), b = point_at(mesh, c[1]);
          double fade = 0;
          for (double s : {s0, s1}) {
            const double n = lerp(num[0], num[1], s),
                         d = lerp(den[0], den[1], s);
            // d <= 0 only where the segment was clipped at den = 0, where num >
            // 0: the test is +inf
            fade += th.suggestive > 0 && d > 0
                        ? clamp01((n / d - th.suggestive) / th.suggestive)
                        : 1.0;
          }
          emit(LineType::suggestive, add(a, scale(sub(b, a), s0)),
               add(a, scale(sub(b, a), s1)),
               s0 == 0 ? key_of(c[0]) : kInsideFace,
               s1 == 1 ? key_of(c[1]) : kInsideFace, fade / 2);
        }
      }
    }

    // Ridges (k1 along dir1, a maximum) and valleys (k2 along dir2, a minimum).
    for (int kind = 0; kind < 2; ++kind) {
      const bool ridge = kind == 0;
      if (!(ridge ? sel.ridges : sel.valleys))
        continue;
      double e[3];
      V3 mean_dir{0, 0, 0};
      bool ok = true;
      const V3 dir0 = to_double(ridge ? field.dir1[v[0]] : field.dir2[v[0]]);
      for (int j = 0; j < 3; ++j) {
        const std::uint32_t i = v[j];
        const double k1 = field.k1[i], k2 = field.k2[i];
        ok = ok && (ridge ? k1 > std::fabs(k2) : k2 < -std::fabs(k1));
        const V3 d = to_double(ridge ? field.dir1[i] : field.dir2[i]);
        const double sign = dot(d, dir0) < 0 ? -1 : 1;
        e[j] = sign * (ridge ? field.dcurv[i][0] : field.dcurv[i][3]);
        mean_dir = add(mean_dir, scale(d, sign));
      }
      if (!ok || !face_crossings(v, e, c))
        continue;
      // Gradient of the linear interpolant of e: sum_j e_j (n x (opposite
      // edge)) / (2 area).
      const V3 n = scale(normal2, 1 / area2);
      V3 grad{0, 0, 0};
      for (int j = 0; j < 3; ++j)
        grad = add(grad, scale(cross(n, sub(p[(j + 2) % 3], p[(j + 1) % 3])),
                               e[j] / area2));
      const double slope = dot(grad, mean_dir);
      if (ridge ? !(slope < 0) : !(slope > 0))
        continue;
      auto k_at = [&](const Crossing &x) {
        auto kv = [&](std::uint32_t i) {
          return ridge ? double(field.k1[i]) : -double(field.k2[i]);
        };
        return at(x, kv);
      };
      const double kk = 0.5 * (k_at(c[0]) + k_at(c[1]));
      if (!(kk > th.ridge))
        continue;
      const double strength =
          th.ridge > 0 ? clamp01((kk - th.ridge) / th.ridge) : 1.0;
      emit(ridge ? LineType::ridge : LineType::valley, point_at(mesh, c[0]),
           point_at(mesh, c[1]), key_of(c[0]), key_of(c[1]), strength);
    }
  }
  return out;
}

} // namespace isocurv::lines
