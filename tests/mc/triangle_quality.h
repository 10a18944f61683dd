#pragma once
// Triangle quality measures for the mesher tests.
#include <algorithm>
#include <cmath>

#include "core/mesh.h"

namespace isocurv::test {

// Smallest area and the share of triangles whose smallest angle is under one degree (unit
// spacing: areas in voxel faces).
struct Quality {
  double min_area = 1e300;
  double thin_share = 0;
  std::size_t slivers = 0;  ///< triangles under 1e-6 (voxel faces at unit spacing)
};

inline Quality quality(const Mesh& m, double unit_area = 1) {
  Quality q;
  std::size_t thin = 0;
  for (const Tri& t : m.triangles) {
    double p[3][3];
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = m.positions[t[k]][c];
    double len2[3];
    for (int k = 0; k < 3; ++k) {
      const double* a = p[(k + 1) % 3];
      const double* b = p[(k + 2) % 3];
      len2[k] = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
    }
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double v[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    q.min_area = std::min(q.min_area, area / unit_area);
    q.slivers += area < 1e-6 * unit_area;
    // The smallest angle faces the shortest edge: sin = 2 area / (product of the other two).
    const int s = int(std::min_element(len2, len2 + 3) - len2);
    const double others = std::sqrt(len2[(s + 1) % 3] * len2[(s + 2) % 3]);
    const double angle = others > 0 ? std::asin(std::min(1.0, 2 * area / others)) : 0;
    if (angle < M_PI / 180) ++thin;
  }
  q.thin_share = m.triangles.empty() ? 0 : double(thin) / double(m.triangles.size());
  return q;
}

}  // namespace isocurv::test
