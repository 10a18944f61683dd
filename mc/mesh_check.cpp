#include "mc/mesh_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "core/mesh_measures.h"
#include "core/union_find.h"

namespace isocurv::mc {
namespace {

// Adding +0 turns -0 into +0, so equal positions have equal bits.
Vec3f canonical(const Vec3f& p) { return {p[0] + 0.0f, p[1] + 0.0f, p[2] + 0.0f}; }

struct PositionHash {
  std::size_t operator()(const Vec3f& p) const {
    std::uint32_t b[3];
    std::memcpy(b, p.data(), sizeof b);
    return (std::size_t(b[0]) * 73856093u) ^ (std::size_t(b[1]) * 19349663u) ^
           (std::size_t(b[2]) * 83492791u);
  }
  std::size_t operator()(const std::array<float, 4>& p) const {
    std::uint32_t l;
    std::memcpy(&l, &p[3], sizeof l);
    return (*this)(Vec3f{p[0], p[1], p[2]}) ^ (std::size_t(l) * 2654435761u);
  }
};

}  // namespace

std::size_t MeshCheck::closed_components() const {
  return std::size_t(std::count_if(component_list.begin(), component_list.end(),
                                   [](const ComponentCheck& c) { return c.closed; }));
}

std::size_t MeshCheck::inward_components() const {
  return std::size_t(
      std::count_if(component_list.begin(), component_list.end(),
                    [](const ComponentCheck& c) { return c.closed && c.signed_volume < 0; }));
}

double MeshCheck::closed_signed_volume() const {
  double v = 0;
  for (const ComponentCheck& c : component_list)
    if (c.closed) v += c.signed_volume;
  return v;
}

MeshCheck check_mesh(const Mesh& mesh, const std::vector<float>* vertex_labels) {
  MeshCheck r;
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangles.size();
  const auto nv = static_cast<std::uint32_t>(mesh.positions.size());
  const bool labelled = vertex_labels && vertex_labels->size() == nv;

  std::unordered_map<Vec3f, std::uint32_t, PositionHash> seen;
  seen.reserve(nv);
  // With labels, the positions are keyed by label too: (x, y, z, label).
  std::unordered_map<std::array<float, 4>, std::uint32_t, PositionHash> seen_in_label;
  if (labelled) seen_in_label.reserve(nv);
  for (std::uint32_t i = 0; i < nv; ++i) {
    const Vec3f p = canonical(mesh.positions[i]);
    const auto [it, fresh] = seen.emplace(p, i);
    if (!labelled) {
      if (!fresh) r.duplicates.push_back({i, it->second});
      continue;
    }
    const auto [same, fresh_in_label] =
        seen_in_label.emplace(std::array<float, 4>{p[0], p[1], p[2], (*vertex_labels)[i] + 0.0f}, i);
    if (!fresh_in_label)
      r.duplicates.push_back({i, same->second});
    else if (!fresh)
      ++r.label_wall_vertices;
  }
  r.duplicate_vertices = r.duplicates.size();

  std::vector<char> used(nv, 0);
  // Directed edge records: (min, max) packed, and +1 when traversed min->max, -1 otherwise.
  std::vector<std::pair<std::uint64_t, int>> half;
  half.reserve(mesh.triangles.size() * 3);
  UnionFind uf(nv);
  std::vector<char> valid(mesh.triangles.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Tri& t = mesh.triangles[f];
    bool bad_index = false;
    for (auto i : t) bad_index |= i >= nv;
    if (bad_index || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.degenerate_triangles;
      if (bad_index) continue;
    }
    valid[f] = 1;
    const std::array<double, 3> n = triangle_area_vector(mesh, t);
    const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (area == 0 && !(t[0] == t[1] || t[1] == t[2] || t[0] == t[2])) ++r.degenerate_triangles;
    r.area += area;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t p = t[k], q = t[(k + 1) % 3];
      used[p] = 1;
      if (p == q) continue;
      const std::uint32_t lo = std::min(p, q), hi = std::max(p, q);
      half.emplace_back((std::uint64_t(lo) << 32) | hi, p < q ? 1 : -1);
      uf.unite(p, q);
    }
  }
  std::sort(half.begin(), half.end());
  // Vertices (by their union-find root) of components with an unpaired edge.
  std::vector<char> unpaired(nv, 0);
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    int sum = 0;
    while (j < half.size() && half[j].first == half[i].first) sum += half[j++].second;
    const std::size_t count = j - i;
    const VertexPair edge = {std::uint32_t(half[i].first >> 32), std::uint32_t(half[i].first)};
    ++r.edges;
    if (count == 1) {
      ++r.boundary_edges;
    } else {
      if (count > 2) r.non_manifold.push_back(edge);
      if (sum != 0) r.misoriented.push_back(edge);
    }
    if (sum != 0) unpaired[uf.find(edge[0])] = 1;
    i = j;
  }
  r.non_manifold_edges = r.non_manifold.size();
  r.misoriented_edges = r.misoriented.size();

  std::size_t referenced = 0;
  std::vector<std::uint32_t> component_of(nv, ~0u);  // indexed by root
  for (std::uint32_t i = 0; i < nv; ++i) {
    if (!used[i]) {
      ++r.unreferenced_vertices;
      continue;
    }
    ++referenced;
    const std::uint32_t root = uf.find(i);
    if (component_of[root] == ~0u) {
      component_of[root] = std::uint32_t(r.component_list.size());
      ComponentCheck c;
      c.first_vertex = i;
      c.closed = !unpaired[root];
      r.component_list.push_back(c);
    }
  }
  r.components = r.component_list.size();
  // Signed volumes relative to each component's first vertex (exact for closed components
  // whatever the origin; the offset keeps far-from-origin meshes precise).
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!valid[f]) continue;
    const Tri& t = mesh.triangles[f];
    ComponentCheck& c = r.component_list[component_of[uf.find(t[0])]];
    ++c.triangles;
    c.signed_volume += signed_volume_term(mesh, t, mesh.positions[c.first_vertex]);
  }
  r.euler = (long long)referenced - (long long)r.edges + (long long)r.triangles;
  return r;
}

}  // namespace isocurv::mc
