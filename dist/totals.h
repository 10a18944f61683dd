#pragma once
// The whole surface's totals from its pieces, each counted once: vertices, edges and triangles by
// their owner (dist/piece.h), area and enclosed volume over owned triangles, and connected
// components joined across ranks where pieces share a vertex.
// Tested in tests/dist/test_distributed.cpp, python/tests/test_isocurv.py (through its users).
#include <cstdint>

#include "core/mesh.h"
#include "dist/piece.h"
#include "dist/world.h"

namespace isocurv::dist {

/// What isocurv check / extract --json report on one process (mc::MeshCheck), for the whole
/// distributed surface.
struct SurfaceTotals {
  std::int64_t vertices = 0, triangles = 0, edges = 0;
  std::int64_t boundary_edges = 0, non_manifold_edges = 0, misoriented_edges = 0;
  std::int64_t components = 0;
  double area = 0;           ///< world units^2
  double signed_volume = 0;  ///< sum of a . (b x c) / 6 over the triangles (from a common origin)

  long long euler() const { return vertices - edges + triangles; }
  bool watertight() const { return boundary_edges == 0 && non_manifold_edges == 0; }
  /// components - euler / 2 when watertight and consistently oriented; -1 otherwise.
  long long genus() const {
    return watertight() && misoriented_edges == 0 ? components - euler() / 2 : -1;
  }
};

/// Collective: the totals over every rank's piece (the same on every rank). `origin` (world) must
/// be the same point on every rank; the signed volume is taken from it (exact for closed
/// surfaces; an origin near the surface keeps far-away meshes precise).
SurfaceTotals reduce_totals(const World& world, const Piece& piece, const Vec3f& origin);

}  // namespace isocurv::dist
