#include "dist/totals.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "core/huge_pages.h"
#include "core/mesh_measures.h"
#include "core/union_find.h"
#include "dist/detail/bucket_sort.h"

namespace isocurv::dist {
namespace {

// One piece's share: its owned counts, and how its local components meet other pieces.
struct Share {
  std::vector<std::int64_t> counts;  // vertices triangles edges boundary non_manifold misoriented
  double area = 0, volume = 0;
  std::uint32_t components = 0;
  /// (global id, local component) for every vertex of a ghost triangle: where this piece's
  /// components touch the neighbours'.
  std::vector<std::pair<std::int64_t, std::uint32_t>> links;
};

Share piece_share(const Piece& p, const Vec3f& origin) {
  Share s;
  const Mesh& m = p.mesh;
  const std::size_t nv = m.positions.size(), nt = m.triangles.size();
  std::int64_t vertices = 0, edges = 0, boundary = 0, non_manifold = 0, misoriented = 0;
  for (std::size_t v = 0; v < nv; ++v) vertices += p.point_ghost[v] == 0;
  for (std::size_t t = 0; t < p.owned_triangles; ++t) {
    const Tri& tri = m.triangles[t];
    const auto a = triangle_area_vector(m, tri);
    s.area += 0.5 * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    s.volume += signed_volume_term(m, tri, origin);
  }
  // Every use of every edge in the piece: (lower, higher vertex), +-1 for its direction, owner.
  struct Use {
    std::uint64_t edge;
    int dir, owner;
    bool operator<(const Use& o) const { return edge < o.edge; }
  };
  std::vector<Use> uses;
  uses.reserve(nt * 3);
  advise_huge_pages(uses.data(), nt * 3 * sizeof(Use));  // first touches of small pages are slow on VMs
  UnionFind uf(nv);
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      uses.push_back({(std::uint64_t(std::min(a, b)) << 32) | std::max(a, b), a < b ? 1 : -1, p.triangle_owner[t]});
      uf.unite(a, b);
    }
  }
  // Grouped by edge: by lower vertex, then by higher.
  detail::bucket_sort(uses, nv, [](const Use& u) { return std::uint32_t(u.edge >> 32); },
                      [](const Use& a, const Use& b) { return a.edge < b.edge; });
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int sum = 0, owner = uses[i].owner;
    while (j < uses.size() && uses[j].edge == uses[i].edge) {
      sum += uses[j].dir;
      owner = std::min(owner, uses[j].owner);
      ++j;
    }
    if (owner == p.rank) {
      ++edges;
      const std::size_t count = j - i;
      if (count == 1) ++boundary;
      if (count > 2) ++non_manifold;
      if (count > 1 && sum != 0) ++misoriented;
    }
    i = j;
  }
  s.counts = {vertices, std::int64_t(p.owned_triangles), edges, boundary, non_manifold, misoriented};
  // Local components numbered 0.., and the vertices where they meet other pieces.
  std::vector<std::uint32_t> comp(nv, ~0u);
  for (std::uint32_t v = 0; v < nv; ++v) {
    const std::uint32_t r = uf.find(v);
    if (comp[r] == ~0u) comp[r] = s.components++;
  }
  std::vector<char> linked(nv, 0);
  for (std::size_t t = p.owned_triangles; t < nt; ++t)
    for (std::uint32_t v : m.triangles[t]) linked[v] = 1;
  for (std::uint32_t v = 0; v < nv; ++v)
    if (linked[v]) s.links.emplace_back(p.global_ids[v], comp[uf.find(v)]);
  return s;
}

std::vector<char> pack_links(const Share& s) {
  std::vector<char> bytes(sizeof(std::uint32_t) + s.links.size() * (sizeof(std::int64_t) + sizeof(std::uint32_t)));
  char* at = bytes.data();
  std::memcpy(at, &s.components, sizeof s.components);
  at += sizeof s.components;
  for (const auto& [id, c] : s.links) {
    std::memcpy(at, &id, sizeof id);
    std::memcpy(at + sizeof id, &c, sizeof c);
    at += sizeof id + sizeof c;
  }
  return bytes;
}

// Rank 0: the global component count from every piece's local components and links.
std::int64_t join_components(const std::vector<std::vector<char>>& packed) {
  std::vector<std::uint32_t> base;  // each rank's first node
  std::uint32_t nodes = 0;
  for (const auto& b : packed) {
    std::uint32_t c = 0;
    std::memcpy(&c, b.data(), sizeof c);
    base.push_back(nodes);
    nodes += c;
  }
  UnionFind uf(nodes);
  std::unordered_map<std::int64_t, std::uint32_t> first;  // global id -> the first node seen there
  for (std::size_t r = 0; r < packed.size(); ++r) {
    const auto& b = packed[r];
    for (std::size_t at = sizeof(std::uint32_t); at + 12 <= b.size(); at += 12) {
      std::int64_t id;
      std::uint32_t c;
      std::memcpy(&id, b.data() + at, sizeof id);
      std::memcpy(&c, b.data() + at + sizeof id, sizeof c);
      const auto [it, fresh] = first.emplace(id, base[r] + c);
      if (!fresh) uf.unite(it->second, base[r] + c);
    }
  }
  std::int64_t roots = 0;
  for (std::uint32_t n = 0; n < nodes; ++n) roots += uf.find(n) == n;
  return roots;
}

}  // namespace

SurfaceTotals reduce_totals(const World& world, const Piece& piece, const Vec3f& origin) {
  const Share s = piece_share(piece, origin);
  const std::vector<std::int64_t> c = world.sum(s.counts);
  const std::vector<double> d = world.sum(std::vector<double>{s.area, s.volume});
  const auto packed = world.gather(pack_links(s));
  std::int64_t components = world.rank() == 0 ? join_components(packed) : 0;
  components = world.sum(std::vector<std::int64_t>{components})[0];  // rank 0's count, everywhere
  SurfaceTotals t;
  t.vertices = c[0];
  t.triangles = c[1];
  t.edges = c[2];
  t.boundary_edges = c[3];
  t.non_manifold_edges = c[4];
  t.misoriented_edges = c[5];
  t.components = components;
  t.area = d[0];
  t.signed_volume = d[1];
  return t;
}

}  // namespace isocurv::dist
