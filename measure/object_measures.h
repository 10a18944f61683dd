#pragma once
// measure::object_measures: the four Minkowski functionals of every connected component of a
// surface (enclosed volume, area, integral of H, Euler characteristic), the integral of K beside
// them, and the Gauss-Bonnet gap by which each result checks itself.
#include <array>
#include <cstddef>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::measure {

/// The measures of one connected component (triangles sharing vertices), world units.
struct ObjectMeasures {
  std::size_t vertices = 0, triangles = 0, edges = 0;
  std::size_t boundary_edges = 0;  ///< edges in one triangle: the surface is cut (by the box)
  bool closed = false;             ///< no boundary edge
  double area = 0;                 ///< sum of the triangles' areas
  /// Enclosed volume by the divergence theorem (sum of a.(b x c)/6), exact for a closed
  /// component; > 0 when it faces outward (an isosurface's components do). For a cut component,
  /// the volume of the cone from its first vertex: meaningless, reported as is.
  double volume = 0;
  double integral_H = 0;  ///< sum of H A over its vertices (A: the field's mixed area)
  double integral_K = 0;  ///< sum of K A over its vertices
  long long euler = 0;    ///< vertices - edges + triangles
  /// (2 - euler) / 2 for a closed component (the number of handles); -1 when cut.
  long long genus() const { return closed ? (2 - euler) / 2 : -1; }
  /// Gauss-Bonnet's check on the curvature: (integral_K - 2 pi euler) / (2 pi max(1, |euler|))
  /// for a closed component (0 when the estimate is exact), NaN when cut.
  double gauss_bonnet_gap() const;
  std::size_t unmeasured = 0;        ///< vertices flagged Unreliable (their H, K count as 0)
  std::array<double, 6> box{};       ///< xmin, xmax, ymin, ymax, zmin, zmax of its vertices
  std::uint32_t first_vertex = 0;    ///< its lowest vertex id
};

/// The measures of every component of `mesh`, largest area first, then by first vertex.
/// `field` supplies H, K and the per-vertex mixed area ("Area"; when it is absent, a third of
/// each adjacent triangle's area is used) and the Unreliable flags; H and K must have one value
/// per vertex. Triangles with a repeated or out-of-range index are skipped. Deterministic.
/// @throw Error when H or K does not have one value per vertex.
std::vector<ObjectMeasures> object_measures(const Mesh& mesh, const curvature::CurvatureField& field);

/// The sums of `objects` (counts, area, volume, integrals, Euler characteristic; closed when all
/// are; the box around all; first_vertex 0).
ObjectMeasures total(const std::vector<ObjectMeasures>& objects);

}  // namespace isocurv::measure
