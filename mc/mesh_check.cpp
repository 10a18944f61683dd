#include "mc/mesh_check.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace isocurv::mc {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

struct PositionHash {
  std::size_t operator()(const Vec3f& p) const {
    std::uint32_t b[3];
    std::memcpy(b, p.data(), sizeof b);
    return (std::size_t(b[0]) * 73856093u) ^ (std::size_t(b[1]) * 19349663u) ^ (std::size_t(b[2]) * 83492791u);
  }
};

}  // namespace

MeshCheck check_mesh(const Mesh& mesh) {
  MeshCheck r;
  r.vertices = mesh.positions.size();
  r.triangles = mesh.triangles.size();
  const auto nv = static_cast<std::uint32_t>(mesh.positions.size());

  std::unordered_map<Vec3f, std::uint32_t, PositionHash> seen;
  seen.reserve(nv);
  for (std::uint32_t i = 0; i < nv; ++i)
    if (!seen.emplace(mesh.positions[i], i).second) ++r.duplicate_vertices;

  std::vector<char> used(nv, 0);
  // Directed edge records: (min, max) packed, and +1 when traversed min->max, -1 otherwise.
  std::vector<std::pair<std::uint64_t, int>> half;
  half.reserve(mesh.triangles.size() * 3);
  UnionFind uf(nv);
  for (const Tri& t : mesh.triangles) {
    bool bad_index = false;
    for (auto i : t) bad_index |= i >= nv;
    if (bad_index || t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.degenerate_triangles;
      if (bad_index) continue;
    }
    const Vec3f &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) { u[k] = double(b[k]) - a[k]; v[k] = double(c[k]) - a[k]; }
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
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
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i;
    int sum = 0;
    while (j < half.size() && half[j].first == half[i].first) sum += half[j++].second;
    const std::size_t count = j - i;
    ++r.edges;
    if (count == 1) ++r.boundary_edges;
    else if (count > 2) ++r.non_manifold_edges;
    else if (sum != 0) ++r.misoriented_edges;
    i = j;
  }
  std::size_t referenced = 0;
  for (std::uint32_t i = 0; i < nv; ++i) {
    if (!used[i]) { ++r.unreferenced_vertices; continue; }
    ++referenced;
    if (uf.find(i) == i) ++r.components;
  }
  r.euler = (long long)referenced - (long long)r.edges + (long long)r.triangles;
  return r;
}

}  // namespace isocurv::mc
