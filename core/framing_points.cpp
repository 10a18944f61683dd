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
  const auto largest_at = std::max_element(area.begin(), area.end());
  const double largest = *largest_at;
  if (!(largest > 0)) return all();
  // Each component's box (per root), for its extent beside the largest component's.
  std::vector<std::array<float, 6>> box(n, {1e30f, 1e30f, 1e30f, -1e30f, -1e30f, -1e30f});
  for (std::size_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a) {
      box[root[v]][a] = std::min(box[root[v]][a], mesh.positions[v][a]);
      box[root[v]][3 + a] = std::max(box[root[v]][3 + a], mesh.positions[v][a]);
    }
  auto extent = [&](std::size_t r) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += double(box[r][3 + a] - box[r][a]) * (box[r][3 + a] - box[r][a]);
    return std::sqrt(d2);
  };
  const double largest_extent = extent(std::size_t(largest_at - area.begin()));
  const double edge = mean_edge_length(mesh);
  std::vector<std::int8_t> kept(n, -1);  // per root: unknown, no, yes
  for (std::size_t v = 0; v < n; ++v) {
    std::int8_t& k = kept[root[v]];
    const std::uint32_t r = root[v];
    if (k < 0)
      k = area[r] >= kSpeckAreaFraction * largest ||
          (extent(r) >= kSpeckExtentFraction * largest_extent &&
           area[r] >= kThickPartEdges * edge * extent(r));
    if (k) out.push_back(to_d(mesh.positions[v]));
  }
  return out;
}

}  // namespace isocurv
