#include "dist/piece.h"

#include <algorithm>
#include <climits>
#include <numeric>

#include "core/error.h"
#include "core/huge_pages.h"
#include "dist/detail/bucket_sort.h"

namespace isocurv::dist {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

std::uint32_t key_z(std::uint64_t key) { return std::uint32_t((key >> 2) & 0xfffffu); }

}  // namespace

std::vector<int> triangle_owners(const Mesh& local, const Slabs& slabs) {
  const auto& keys = local.edge_keys;
  if (keys.size() != local.positions.size()) throw Error("cut_piece: the local extraction has no edge keys");
  std::vector<int> owner(local.triangles.size());
  for (std::size_t t = 0; t < owner.size(); ++t) {
    const Tri& tri = local.triangles[t];
    const std::uint32_t z = std::min({key_z(keys[tri[0]]), key_z(keys[tri[1]]), key_z(keys[tri[2]])});
    owner[t] = slabs.owner_of_cell(int(z) + slabs.key_origin_z);
  }
  return owner;
}

Piece cut_piece(const Mesh& local, const Slabs& slabs, int rank) {
  const std::size_t nv = local.positions.size(), nt = local.triangles.size();
  const auto& keys = local.edge_keys;

  // Owners: triangles by their lowest key z; vertices by the lowest owner around them.
  const std::vector<int> tri_owner = triangle_owners(local, slabs);
  std::vector<int> vert_owner(nv, INT_MAX);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t v : local.triangles[t]) vert_owner[v] = std::min(vert_owner[v], tri_owner[t]);
  // The owned triangles' vertices, then the ghost ring: the other triangles using one of them.
  std::vector<char> near(nv, 0);
  for (std::size_t t = 0; t < nt; ++t)
    if (tri_owner[t] == rank)
      for (std::uint32_t v : local.triangles[t]) near[v] = 1;
  std::vector<std::uint32_t> owned, ring;
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& tri = local.triangles[t];
    if (tri_owner[t] == rank)
      owned.push_back(std::uint32_t(t));
    else if (near[tri[0]] || near[tri[1]] || near[tri[2]])
      ring.push_back(std::uint32_t(t));
  }
  // Vertices in increasing global id, so that a piece's order does not depend on the local
  // extraction's (which depends on how far the slab reaches).
  std::vector<char> used(nv, 0);
  for (const auto* list : {&owned, &ring})
    for (std::uint32_t t : *list)
      for (std::uint32_t v : local.triangles[t]) used[v] = 1;
  Piece p;
  p.rank = rank;
  {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> by_key;  // sorted without indirection
    by_key.reserve(nv);
    for (std::uint32_t v = 0; v < nv; ++v)
      if (used[v]) by_key.emplace_back(keys[v], v);
    std::sort(by_key.begin(), by_key.end());
    p.local_vertex.reserve(by_key.size());
    for (const auto& [key, v] : by_key) p.local_vertex.push_back(v);
  }
  std::vector<std::uint32_t> index(nv, kNone);
  const std::size_t n = p.local_vertex.size();
  p.mesh.positions.resize(n);
  p.global_ids.resize(n);
  p.point_ghost.resize(n);
  p.vertex_owner.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t v = p.local_vertex[i];
    index[v] = std::uint32_t(i);
    p.mesh.positions[i] = local.positions[v];
    p.global_ids[i] = std::int64_t(keys[v]);
    p.vertex_owner[i] = vert_owner[v];
    p.point_ghost[i] = vert_owner[v] == rank ? 0 : kDuplicate;
  }
  // Triangles renumbered, each list in the order of its (rotated to start at the lowest id)
  // global-id triple: the same order on every rank count.
  // (Piece vertex numbers increase with the global ids, so they order the triples alike.)
  auto renumbered = [&](std::vector<std::uint32_t>& list) {
    struct Rotated {
      std::uint32_t v[3], t;
    };
    std::vector<Rotated> order;
    order.reserve(list.size());
    for (std::uint32_t t : list) {
      Tri tri = local.triangles[t];
      for (auto& v : tri) v = index[v];
      const int k = tri[0] < tri[1] ? (tri[0] < tri[2] ? 0 : 2) : (tri[1] < tri[2] ? 1 : 2);
      order.push_back({{tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]}, t});
    }
    detail::bucket_sort(order, n, [](const Rotated& r) { return r.v[0]; }, [](const Rotated& a, const Rotated& b) {
      return a.v[1] != b.v[1] ? a.v[1] < b.v[1] : a.v[2] < b.v[2];
    });
    for (const Rotated& r : order) {
      const std::uint32_t t = r.t;
      Tri tri = local.triangles[t];
      for (auto& v : tri) v = index[v];
      p.mesh.triangles.push_back(tri);
      p.triangle_owner.push_back(tri_owner[t]);
      p.cell_ghost.push_back(tri_owner[t] == rank ? 0 : kDuplicate);
    }
  };
  const std::size_t kept = owned.size() + ring.size();
  resize_in_huge_pages(p.mesh.triangles, 0);
  p.mesh.triangles.reserve(kept);
  advise_huge_pages(p.mesh.triangles.data(), kept * sizeof(Tri));
  p.triangle_owner.reserve(kept);
  p.cell_ghost.reserve(kept);
  renumbered(owned);
  renumbered(ring);
  p.owned_triangles = owned.size();
  return p;
}

}  // namespace isocurv::dist
