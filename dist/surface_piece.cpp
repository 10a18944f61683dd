#include "dist/surface_piece.h"

#include <cstring>

namespace isocurv::dist {

RankPiece::RankPiece(const World& world, const Mesh& local, const Slabs& slabs, const Piece& piece)
    : world_(world), slabs_(slabs) {
  owned_vertices.assign(local.positions.size(), 0);
  for (std::size_t i = 0; i < piece.local_vertex.size(); ++i)
    if (!piece.point_ghost[i]) owned_vertices[piece.local_vertex[i]] = 1;
  const std::vector<int> owners = triangle_owners(local, slabs);
  owned_triangles.assign(owners.size(), 0);
  for (std::size_t t = 0; t < owners.size(); ++t) owned_triangles[t] = owners[t] == world.rank();
}

std::vector<double> RankPiece::all(const std::vector<double>& mine) const {
  check_peers(world_);
  std::vector<char> bytes(mine.size() * sizeof(double));
  if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  std::vector<char> joined;
  for (const std::vector<char>& part : world_.gather(bytes)) joined.insert(joined.end(), part.begin(), part.end());
  joined = world_.broadcast(std::move(joined));
  std::vector<double> out(joined.size() / sizeof(double));
  if (!out.empty()) std::memcpy(out.data(), joined.data(), out.size() * sizeof(double));
  return out;
}

std::vector<std::int64_t> RankPiece::sum(const std::vector<std::int64_t>& mine) const {
  check_peers(world_);
  return world_.sum(mine);
}

bool RankPiece::holds_cells_at(int z) const { return slabs_.owner_of_cell(z) == world_.rank(); }

}  // namespace isocurv::dist
