#pragma once
// measure::object_measures: the four Minkowski functionals of every connected component of a
// surface (enclosed volume, area, integral of H, Euler characteristic), the integral of K beside
// them, and the Gauss-Bonnet gap by which each result checks itself.
// Tested in tests/measure/test_object_measures.cpp, tests/measure/test_measure_accuracy.cpp.
#include <array>
#include <cstddef>
#include <vector>

#include "core/mesh.h"
#include "curvature/adaptive_scale.h"
#include "curvature/curvature_field.h"

namespace isocurv::measure {

/// The measures of one connected component (triangles sharing vertices), world units.
struct ObjectMeasures {
  std::size_t vertices = 0, triangles = 0, edges = 0;
  std::size_t boundary_edges = 0;  ///< edges in one triangle: the surface is cut (by the box)
  bool closed = false;             ///< no boundary edge
  double area = 0;                 ///< the area of its patches (object_measures)
  /// The area of the mesh's own flat triangles (what `isocurv check` and stats.json report):
  /// larger than `area` on rough surfaces, whose triangles tilt with the noise.
  double mesh_area = 0;
  /// Enclosed volume by the divergence theorem (the integral of x.n dA / 3 over its patches),
  /// exact for the closed surface the patches make; > 0 when it faces outward (an isosurface's
  /// components do). For a cut component, the volume of the cone from its first vertex:
  /// meaningless, reported as is.
  double volume = 0;
  double integral_H = 0;  ///< the integral of H dA (object_measures)
  /// The per-vertex curvature's own total: K times each vertex's area (the field's "Area", else
  /// a third of its triangles'), so that an estimate which keeps Gauss-Bonnet with its areas
  /// (Meyer's angle defects) has a gap of zero whatever the patches do; where the field places
  /// its vertices on another surface (surface points: the volume estimator), K over the patches
  /// through those points (the areas of that surface, not of the marching-cubes staircase).
  double integral_K = 0;
  long long euler = 0;    ///< vertices - edges + triangles
  /// (2 - euler) / 2 for a closed component (the number of handles); -1 when cut.
  long long genus() const { return closed ? (2 - euler) / 2 : -1; }
  /// Gauss-Bonnet's check on the curvature: (integral_K - 2 pi euler) / (2 pi max(1, |euler|))
  /// for a closed component (0 when the estimate is exact), NaN when cut.
  double gauss_bonnet_gap() const;
  /// The number of handles the curvature's integral implies, 1 - integral_K / (4 pi), for a
  /// closed component (NaN when cut). Below genus() when the mesh has handles narrower than the
  /// curvature's scale (a CT's noise tunnels): the smoothed surface the curvature describes does
  /// not have them, so their -4 pi each is missing from integral_K (has_fine_handles).
  double curvature_genus() const;
  /// True for a resolved, closed component whose curvature_genus() is under its genus() by more
  /// than kFineHandles and a tenth: its Gauss-Bonnet gap counts handles finer than the
  /// curvature scale, not an error of the curvature on the rest.
  bool has_fine_handles() const;
  std::size_t unmeasured = 0;        ///< vertices flagged Unreliable (their H, K count as 0)
  std::array<double, 6> box{};       ///< xmin, xmax, ymin, ymax, zmin, zmax of its vertices
  std::uint32_t first_vertex = 0;    ///< its lowest vertex id
  /// Measured over the mesh's own vertices although the field had surface points: they changed
  /// its area or volume by more than kMaxSurfaceChange (a component below the estimator's scale).
  bool on_vertices = false;
  /// The largest per-vertex smoothing scale among its vertices (the field's "Scale" array, world
  /// units; 0 without one).
  double scale = 0;
  /// False when the component is smaller than its curvature's scale resolves: the shortest side
  /// of its box under kResolvedExtent times `scale`. Its integrals of H and K, and its
  /// Gauss-Bonnet gap, then say more about the smoothing than about the object.
  bool resolved = true;
};

/// A component whose box's shortest side is under this many times its largest smoothing scale
/// is not resolved (ObjectMeasures::resolved): 2 / curvature::kShapeScale, the diameter of the
/// smallest ball whose curvature the per-vertex choice measures at that scale.
inline constexpr double kResolvedExtent = 2.0 / curvature::kShapeScale;

/// has_fine_handles: the least number of handles the curvature may miss before it is said.
inline constexpr double kFineHandles = 2;

/// Surface points that change a component's area (or a closed one's volume) by more than this
/// fraction are not used for it (ObjectMeasures::on_vertices). On objects the estimator resolves
/// they change them by a few percent (binary masks: the voxel staircase, about 8% of the area).
inline constexpr double kMaxSurfaceChange = 0.5;

/// The measures of every component of `mesh`, largest area first, then by first vertex.
/// What is integrated, when `field` has one normal per vertex (every estimator's field):
///  - the positions: the field's surface_points where it has one per vertex (the volume
///    estimator's: on binary volumes the smoothed isosurface moved out by the smoothing's
///    shrinkage, on grey-level ones the marching-cubes vertex moved along its cube edge by the
///    interpolation's second-order error), else the mesh's vertices;
///  - over each triangle, the quadratic patch through its three positions whose edge curves are
///    orthogonal to the field's unit normals at both ends (Nagata 2005: x(t) = x0 (1 - t) + x1 t
///    - c t (1 - t), exact on a sphere; flat where a normal is missing or the two are nearly
///    opposed); neighbours share their edge curves, so a closed mesh gives a closed surface;
///  - area |(x_u x x_v).nbar|, the area element projected on the unit normal interpolated from
///    the field's (so the roughness noise gives a scan's triangles does not count as area:
///    +0.5% on 8-bit CT-like solids without it), volume (x - o).(x_u x x_v) / 3 (o the
///    component's first position; noise averages out of it) and H and K interpolated linearly
///    from the vertices times the area element, by a symmetric 6-point rule of degree 4 (exact
///    for the volume, a polynomial of degree 4).
/// Without normals, the flat triangles of the mesh's vertices and H times the per-vertex mixed
/// area ("Area"; when it is absent, a third of each adjacent triangle's area). The integral of
/// K is that per-vertex sum on both paths unless the field has surface points
/// (ObjectMeasures::integral_K). Unreliable
/// vertices' H and K count as 0 either way. The Euler characteristic, the components and the box
/// always come from the mesh (its connectivity and vertices). H and K must have one value per
/// vertex. Triangles with a repeated or out-of-range index are skipped. The patches are
/// integrated in parallel (TBB) and summed in triangle order: deterministic, whatever the threads.
/// @throw Error when H or K does not have one value per vertex.
std::vector<ObjectMeasures> object_measures(const Mesh& mesh, const curvature::CurvatureField& field);

/// The sums of `objects` (counts, area, volume, integrals, Euler characteristic; closed and
/// on_vertices when all, or any, are; the box around all; first_vertex 0).
ObjectMeasures total(const std::vector<ObjectMeasures>& objects);

/// The sum of the objects' genera, or -1 when one of them is not closed (its genus undefined).
long long genus_sum(const std::vector<ObjectMeasures>& objects);

}  // namespace isocurv::measure
