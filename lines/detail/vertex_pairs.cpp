#include "lines/detail/vertex_pairs.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace isocurv::lines::detail {
namespace {

bool repeated(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

// Triangle blocks of the counting sort: each has its own count per vertex, and its entries follow
// the earlier blocks' in every row, so the rows come out in triangle order whatever runs where.
constexpr std::size_t kBlocks = 2;

}  // namespace

void build_vertex_pairs(const Mesh& mesh, VertexPairs& out) {
  const std::size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  const std::size_t blocks = nf < 65536 ? 1 : kBlocks;
  auto block_faces = [&](std::size_t b) {
    return std::pair<std::size_t, std::size_t>(nf * b / blocks, nf * (b + 1) / blocks);
  };
  // 1. Each block's corners per vertex.
  std::vector<std::vector<std::uint32_t>>& cursor = out.cursors;
  cursor.resize(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    cursor[b].assign(nv, 0);
    const auto [begin, end] = block_faces(b);
    for (std::size_t f = begin; f < end; ++f) {
      const Tri t = mesh.triangles[f];  // a copy: the stores below cannot alias it
      if (!repeated(t)) ++cursor[b][t[0]], ++cursor[b][t[1]], ++cursor[b][t[2]];
    }
  });
  // 2. Row starts; each block's cursor becomes where its first entry of the row goes.
  out.offsets.resize(nv + 1);
  std::uint32_t start = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    out.offsets[v] = start;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::uint32_t count = cursor[b][v];
      cursor[b][v] = start;
      start += count;
    }
  }
  out.offsets[nv] = start;
  // 3. Each block places its pairs.
  out.pairs.resize(2 * std::size_t(start));
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    std::uint32_t* pairs = out.pairs.data();
    std::uint32_t* row = cursor[b].data();
    const auto [begin, end] = block_faces(b);
    for (std::size_t f = begin; f < end; ++f) {
      const Tri t = mesh.triangles[f];  // a copy: the stores below cannot alias it
      if (repeated(t)) continue;
      for (int j = 0; j < 3; ++j) {
        std::uint32_t* p = pairs + 2 * std::size_t(row[t[j]]++);
        p[0] = t[(j + 1) % 3], p[1] = t[(j + 2) % 3];
      }
    }
  });
}

}  // namespace isocurv::lines::detail
