#pragma once
// The area of a geodesic disc on a triangle mesh: geodesic distances from a
// vertex by fast marching over the triangles (Kimmel and Sethian 1998: each
// triangle's update unfolds it into the plane and propagates a straight front;
// an edge otherwise), then the area of the region where the distance, linear
// over each triangle, is at most r.
#include <cstdint>
#include <utility>
#include <vector>

#include "core/mesh.h"
#include "features/detail/mesh_graph.h"

namespace isocurv::features::detail {

/// Scratch for one thread, sized to the mesh on first use.
struct GeodesicScratch {
  std::vector<double> dist;
  std::vector<std::uint32_t> stamp; ///< dist[v] is valid when stamp[v] == mark
  std::vector<std::uint8_t> done;   ///< finalised (valid with the stamp)
  std::vector<std::uint32_t>
      touched; ///< vertices given a distance in this call
  std::vector<std::pair<double, std::uint32_t>> heap;
  std::uint32_t mark = 0;
};

struct GeodesicDisc {
  double area = 0;               ///< area where distance <= r
  bool touches_boundary = false; ///< an open-boundary vertex lies within r
};

/// The geodesic disc of radius r around vertex v. `max_edge` bounds the mesh's
/// edge length: the march runs until r + max_edge so every triangle the disc's
/// rim crosses has final distances.
GeodesicDisc geodesic_disc(const Mesh &mesh, const MeshGraph &graph,
                           std::uint32_t v, double r, double max_edge,
                           GeodesicScratch &scratch);

/// Fraction of a triangle's area where a linear function with corner values f0,
/// f1, f2 is >= 0.
double positive_fraction(double f0, double f1, double f2);

/// Distance at corner c of a triangle whose corners a and b have distances da
/// and db, by unfolding (the straight front through a and b); the smaller edge
/// path when the front would not enter the triangle through edge ab.
double triangle_update(const Vec3f &a, const Vec3f &b, const Vec3f &c,
                       double da, double db);

} // namespace isocurv::features::detail
