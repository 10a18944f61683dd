#pragma once
// A rank's piece as the estimators see it (core/surface_piece.h): which vertices and triangles of
// its local extraction it owns, and the reductions over the ranks that the whole-surface
// quantities (the volume estimator's automatic scale and weak-gradient threshold, the AO scale)
// need.
// Tested in tests/dist/test_distributed.cpp and tests/curvature/volume_piece_test.cpp.
#include "core/mesh.h"
#include "core/surface_piece.h"
#include "dist/piece.h"
#include "dist/slabs.h"
#include "dist/world.h"

namespace isocurv::dist {

class RankPiece final : public SurfacePiece {
 public:
  /// `local`: the rank's local extraction (edge keys filled), from which `piece` was cut
  /// (cut_piece(local, slabs, world.rank())). `world` must outlive this object.
  RankPiece(const World& world, const Mesh& local, const Slabs& slabs, const Piece& piece);

  std::vector<double> all(const std::vector<double>& mine) const override;
  std::vector<std::int64_t> sum(const std::vector<std::int64_t>& mine) const override;
  /// The slab's rank (Slabs::owner_of_cell): its read covers the slab, the margin and the apron.
  bool holds_cells_at(int z) const override;

 private:
  const World& world_;
  Slabs slabs_;
};

}  // namespace isocurv::dist
