#pragma once
// Meshes for the lines tests, built directly, with curvature from the double
// reference.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/reference.h"

namespace isocurv::test {

constexpr double kPi = 3.14159265358979323846;

struct Surface {
  Mesh mesh;
  curvature::CurvatureField field;
};

/// Icosahedron subdivided `level` times onto the unit sphere, scaled by (sx,
/// sy, sz) and moved by `centre`; outward winding.
inline Mesh icosphere(int level, std::array<double, 3> scale = {1, 1, 1},
                      std::array<double, 3> centre = {0, 0, 0}) {
  using P = std::array<double, 3>;
  auto unit = [](P p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return P{p[0] / n, p[1] / n, p[2] / n};
  };
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<P> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                      {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                      {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  Triangles f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto &q : p)
    q = unit(q);
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end())
        return it->second;
      p.push_back(
          unit({p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]}));
      return mid[key] = std::uint32_t(p.size() - 1);
    };
    Triangles g;
    for (const Tri &q : f) {
      const std::uint32_t ab = midpoint(q[0], q[1]), bc = midpoint(q[1], q[2]),
                          ca = midpoint(q[2], q[0]);
      g.push_back({q[0], ab, ca});
      g.push_back({q[1], bc, ab});
      g.push_back({q[2], ca, bc});
      g.push_back({ab, bc, ca});
    }
    f.swap(g);
  }
  Mesh m;
  for (const auto &q : p)
    m.positions.push_back({float(centre[0] + scale[0] * q[0]),
                           float(centre[1] + scale[1] * q[1]),
                           float(centre[2] + scale[2] * q[2])});
  m.triangles = f;
  return m;
}

/// A regular nu x nv grid of quads (split into triangles) mapped by `at(s, t)`,
/// s, t in [0, 1] (periodic in s and/or t when asked); winding (ds x dt) is the
/// outward side.
inline Mesh
grid_mesh(int nu, int nv, bool wrap_u, bool wrap_v,
          const std::function<std::array<double, 3>(double, double)> &at) {
  Mesh m;
  const int pu = wrap_u ? nu : nu + 1, pv = wrap_v ? nv : nv + 1;
  for (int j = 0; j < pv; ++j)
    for (int i = 0; i < pu; ++i) {
      const auto q = at(double(i) / nu, double(j) / nv);
      m.positions.push_back({float(q[0]), float(q[1]), float(q[2])});
    }
  auto id = [&](int i, int j) {
    return std::uint32_t((j % pv) * pu + (i % pu));
  };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

/// Torus about z, major radius R, tube radius r.
inline Mesh torus_mesh(double R, double r, int nu, int nv) {
  return grid_mesh(nu, nv, true, true, [&](double s, double t) {
    const double u = 2 * kPi * s, v = 2 * kPi * t;
    return std::array<double, 3>{(R + r * std::cos(v)) * std::cos(u),
                                 (R + r * std::cos(v)) * std::sin(u),
                                 r * std::sin(v)};
  });
}

/// Curvature of `mesh` from the double reference, with `normals` when given.
inline Surface with_curvature(Mesh mesh,
                              const std::vector<Vec3f> *normals = nullptr) {
  curvature::Options o;
  o.vertex_normals = normals;
  Surface s;
  s.field = curvature::estimate_reference(mesh, o);
  s.mesh = std::move(mesh);
  return s;
}

inline double mean_edge(const Mesh &m) {
  double sum = 0;
  for (const Tri &t : m.triangles)
    for (int j = 0; j < 3; ++j) {
      const Vec3f &a = m.positions[t[j]], &b = m.positions[t[(j + 1) % 3]];
      sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) +
                       double(a[1] - b[1]) * (a[1] - b[1]) +
                       double(a[2] - b[2]) * (a[2] - b[2]));
    }
  return sum / (3.0 * m.triangles.size());
}

inline double seg_length(const Vec3f &a, const Vec3f &b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return std::sqrt(x * x + y * y + z * z);
}

} // namespace isocurv::test
