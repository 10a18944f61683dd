#include "core/mesh_measures.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace isocurv {

double bounding_box_diagonal(const Mesh& mesh) {
  if (mesh.positions.empty()) return 0;
  Vec3f lo = mesh.positions[0], hi = lo;
  for (const Vec3f& p : mesh.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  double d = 0;
  for (int a = 0; a < 3; ++a) d += double(hi[a] - lo[a]) * (hi[a] - lo[a]);
  return std::sqrt(d);
}

double mean_edge_length(const Mesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  return edge_length_sum(mesh)[0] / (3.0 * static_cast<double>(mesh.triangles.size()));
}

std::array<double, 2> edge_length_sum(const Mesh& mesh, const std::vector<std::uint8_t>* only) {
  double sum = 0, count = 0;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (only && !(i < only->size() && (*only)[i])) continue;
    const Tri& t = mesh.triangles[i];
    for (int e = 0; e < 3; ++e) {
      const Vec3f& a = mesh.positions[t[e]];
      const Vec3f& b = mesh.positions[t[(e + 1) % 3]];
      const double dx = double(b[0]) - a[0], dy = double(b[1]) - a[1], dz = double(b[2]) - a[2];
      sum += std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    count += 3;
  }
  return {sum, count};
}

double signed_volume_term(const Mesh& mesh, const Tri& t, const Vec3f& o) {
  double p[3][3];
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) p[j][k] = double(mesh.positions[t[j]][k]) - o[k];
  return (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) -
          p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
          p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) /
         6.0;
}

std::array<double, 3> triangle_area_vector(const Mesh& mesh, const Tri& t) {
  const Vec3f &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = double(b[k]) - a[k];
    v[k] = double(c[k]) - a[k];
  }
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

std::vector<Vec3f> area_weighted_normals(const Mesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  std::vector<std::array<double, 3>> sums(nv, {0, 0, 0});
  for (const Tri& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    const std::array<double, 3> n = triangle_area_vector(mesh, t);
    for (std::uint32_t i : t)
      for (int k = 0; k < 3; ++k) sums[i][k] += n[k];
  }
  std::vector<Vec3f> out(nv);
  for (std::size_t i = 0; i < nv; ++i)
    out[i] = {float(sums[i][0]), float(sums[i][1]), float(sums[i][2])};
  return out;
}

}  // namespace isocurv
