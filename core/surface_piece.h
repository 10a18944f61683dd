#pragma once
// One piece of a surface divided among processes (dist/, `mpirun`): which of the piece's mesh
// vertices and triangles it owns, and the reductions over every piece that the few
// whole-surface quantities need (the volume estimator's automatic scale and weak-gradient
// threshold, the default AO scale). The estimators take `const SurfacePiece*`; a single process
// passes none (nullptr) and everything in its mesh is its own.
//
// Contract: each vertex and triangle of the whole surface is owned by exactly one piece; the
// pieces call the reductions collectively (every piece, the same calls in the same order).
// Tested in tests/curvature/volume_piece_test.cpp.
#include <cstdint>
#include <vector>

namespace isocurv {

class SurfacePiece {
 public:
  virtual ~SurfacePiece() = default;

  /// Per vertex of this piece's mesh: 1 where this piece owns it (the others are its margin:
  /// they give the owned vertices their neighbourhood and are counted by another piece).
  std::vector<std::uint8_t> owned_vertices;
  /// Per triangle of this piece's mesh: 1 where this piece owns it.
  std::vector<std::uint8_t> owned_triangles;

  /// Every piece's `mine` concatenated in piece order, returned on every piece. Collective.
  virtual std::vector<double> all(const std::vector<double>& mine) const = 0;
  /// The element-wise sums of every piece's `mine` (all the same length), on every piece.
  /// Collective.
  virtual std::vector<std::int64_t> sum(const std::vector<std::int64_t>& mine) const = 0;
  /// True on the one piece that holds the volume's data around the cells of index z `z`
  /// (the piece whose slab the cell lies in): that piece measures what lies there.
  virtual bool holds_cells_at(int z) const = 0;
};

/// True when vertex `v` counts for `piece` (always without a piece).
inline bool owns_vertex(const SurfacePiece* piece, std::size_t v) {
  return !piece || piece->owned_vertices[v] != 0;
}

/// The `k`-th smallest (0-based) of every piece's `mine` together (without a piece, of `mine`),
/// for values that are positive or +infinity (no NaN): exact, by two rounds of 16-bit radix
/// histograms summed over the pieces (SurfacePiece::sum), so no piece gathers the others'
/// values. Collective. Requires k below the total count.
float kth_smallest_positive(const SurfacePiece* piece, std::vector<float> mine, std::uint64_t k);

/// The total count of `n` over the pieces (`n` without a piece). Collective.
std::uint64_t total_count(const SurfacePiece* piece, std::uint64_t n);

}  // namespace isocurv
