#include "core/framing_points.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/mesh_measures.h"

namespace isocurv {
namespace {

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// Labels each vertex with its connected component's root (vertices joined by triangles).
std::vector<std::uint32_t> component_roots(const Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (const Tri& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const std::uint32_t a = find_root(parent, t[0]);
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t b = find_root(parent, t[k]);
      if (a != b) parent[b] = a;
    }
  }
  for (std::uint32_t v = 0; v < n; ++v) parent[v] = find_root(parent, v);
  return parent;
}

std::array<double, 3> to_d(const Vec3f& p) { return {p[0], p[1], p[2]}; }

}  // namespace

std::vector<std::array<double, 3>> framing_points(const Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<std::array<double, 3>> out;
  out.reserve(n);
  auto all = [&] {
    for (const Vec3f& p : mesh.positions) out.push_back(to_d(p));
    return out;
  };
  if (mesh.triangles.empty()) return all();
  const std::vector<std::uint32_t> root = component_roots(mesh);
  std::vector<double> area(n, 0.0);  // per root
  for (const Tri& t : mesh.triangles) {
    if (t[0] >= n || t[1] >= n || t[2] >= n) continue;
    const std::array<double, 3> a = triangle_area_vector(mesh, t);
    area[root[t[0]]] += 0.5 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  const double largest = *std::max_element(area.begin(), area.end());
  if (!(largest > 0)) return all();
  for (std::size_t v = 0; v < n; ++v)
    if (area[root[v]] >= kSpeckAreaFraction * largest) out.push_back(to_d(mesh.positions[v]));
  return out;
}

}  // namespace isocurv
