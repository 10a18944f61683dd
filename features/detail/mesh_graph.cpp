#include "features/detail/mesh_graph.h"

#include <algorithm>
#include <utility>

namespace isocurv::features::detail {
namespace {

bool degenerate(const Tri &t) {
  return t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
}

/// Compressed rows from (row, value) pairs sorted by row then value, duplicates
/// removed.
void compress(std::vector<std::pair<std::uint32_t, std::uint32_t>> &pairs,
              std::size_t rows, std::vector<std::uint32_t> &start,
              std::vector<std::uint32_t> &values) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  start.assign(rows + 1, 0);
  for (const auto &p : pairs)
    ++start[p.first + 1];
  for (std::size_t i = 0; i < rows; ++i)
    start[i + 1] += start[i];
  values.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    values[i] = pairs[i].second;
}

} // namespace

MeshGraph build_mesh_graph(const Mesh &mesh) {
  const std::size_t n = mesh.vertex_count();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges, corners;
  edges.reserve(6 * mesh.triangle_count());
  corners.reserve(3 * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Tri &tri = mesh.triangles[t];
    if (degenerate(tri))
      continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = tri[c], b = tri[(c + 1) % 3];
      edges.push_back({a, b});
      edges.push_back({b, a});
      corners.push_back({a, static_cast<std::uint32_t>(t)});
    }
  }
  MeshGraph g;
  g.on_boundary.assign(n, 0);
  // An undirected edge used by one triangle appears once per direction; count
  // before dedup.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> undirected;
  undirected.reserve(edges.size() / 2);
  for (const auto &e : edges)
    if (e.first < e.second)
      undirected.push_back(e);
  std::sort(undirected.begin(), undirected.end());
  for (std::size_t i = 0; i < undirected.size();) {
    std::size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i])
      ++j;
    if (j - i == 1)
      g.on_boundary[undirected[i].first] = g.on_boundary[undirected[i].second] =
          1;
    i = j;
  }
  compress(edges, n, g.vv_start, g.vv);
  compress(corners, n, g.vt_start, g.vt);
  return g;
}

} // namespace isocurv::features::detail
