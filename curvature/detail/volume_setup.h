#pragma once
// Internals the volume estimator's device path and its reference share
// (curvature/volume_estimate.h).
#include <cstdint>
#include <array>
#include <functional>
#include <unordered_map>
#include <vector>

#include "core/mesh.h"
#include "core/surface_piece.h"
#include "curvature/curvature_field.h"
#include "curvature/vertex_corners.h"
#include "curvature/volume_estimate.h"
#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::curvature::detail {

/// The checked inputs of one volume estimate.
struct VolumeSetup {
  volume::GridFrame frame;
  double sigma = 0;  ///< world units
  double voxel = 0;  ///< the largest spacing, world units
  double floor = 0;  ///< the finest scale of the per-vertex choice: min(sigma, kFloorVoxels voxel)
  double max_shift = 0;  ///< VolumePoint::surface: the largest move, kMaxShiftVoxels * voxel
  VolumePoint point = VolumePoint::vertex;
  volume::Inside inside = volume::Inside::Above;
};

/// Checks mesh, sigma and the grid (see volume_estimate) and derives the setup.
VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume, double sigma);

/// How far from a vertex (index units per axis, beyond the B-spline's own support) the estimator
/// may evaluate the field: half a voxel, for rounding (it evaluates at the vertex itself).
openvdb::Vec3d spline_reach(const VolumeSetup& setup);

/// Per-vertex results before the reliability pass: |g| at the vertex (0 where the gradient
/// vanished) and the signed distance (F(x) - isovalue) / |g| from the vertex to the smoothed
/// field's isosurface along the gradient, world units (infinite where the gradient vanished).
struct RawVertex {
  std::vector<float> gradient_norm;
  std::vector<float> shift;
};

/// Where the surface is cut by a dense volume's box: the mesh's open-boundary vertices (marching
/// cubes leaves a surface open exactly where it meets the box). A smoothing around a vertex
/// reaches the cut when the vertex is within kSupportDeviations deviations of one of them; a
/// smoothing that leaves the box elsewhere only sees the background repeated (clamping), which
/// is what the volume would have held. Empty for sparse grids (their data does not stop at a box).
class CutIndex {
 public:
  CutIndex(const Mesh& mesh, const VertexCorners& corners, const volume::GridFrame& frame);
  /// True when a cut vertex lies within `radius` (world units) of p. Not thread-safe (it buckets
  /// the cut by `radius` on first use).
  bool near(const Vec3f& p, double radius) const;

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3f& p) const;
  static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z);
  std::uint64_t key(const Vec3f& p) const;
  std::vector<Vec3f> points;
  mutable double cell = 0;
  mutable std::unordered_map<std::uint64_t, std::vector<Vec3f>> buckets;
};

/// One evaluation of the estimator at setup.sigma for some positions: the field's per-vertex
/// arrays (Normals, k1, k2, dir1, dir2, H, K, dcurv, ShapeIndex, Curvedness, AO), one entry per
/// position, and the raw flags.
struct VolumeEvaluation {
  CurvatureField field;
  RawVertex raw;
  std::size_t bricks = 0;  ///< bricks of every stage summed over the evaluations (device path)
  VolumeStepTimes steps;   ///< summed over the evaluations (device path)
};
using VolumeEvaluate =
    std::function<VolumeEvaluation(const Positions& positions, const VolumeSetup& setup)>;

/// The per-vertex scale choice (volume_estimate.h): what each vertex was measured at.
struct ScaleLadder {
  std::vector<float> scale;           ///< per vertex, world units
  std::vector<std::uint8_t> eroded;   ///< at its final scale: the smoothed isosurface is too far
  std::vector<std::uint8_t> opposed;  ///< at its final scale: the gradient opposes the mesh normal
  std::vector<std::uint8_t> outside;  ///< at its final scale: its smoothing reaches the box's cut
  std::size_t refined = 0;            ///< vertices measured finer than setup.sigma
};

/// Evaluates every vertex of `mesh` at setup.sigma; then, when `finer_scales`, the vertices that
/// do not fit that scale (eroded, opposed or near the box: volume_estimate.h) again at
/// sigma / kScaleStep, and so on down to setup.floor, each keeping the first scale it fits (or
/// the floor's values).
VolumeEvaluation evaluate_with_finer_scales(const Mesh& mesh, const VertexCorners& corners,
                                            VolumeSetup setup, bool finer_scales,
                                            const VolumeEvaluate& evaluate, ScaleLadder& ladder);

/// The number of set flags.
inline std::size_t count_of(const std::vector<std::uint8_t>& flags) {
  std::size_t n = 0;
  for (std::uint8_t f : flags) n += f != 0;
  return n;
}

/// Fills Area, Boundary (the mesh's open boundary, or a smoothing that reaches the cut), Unreliable
/// and the "Scale" array, and resets the unreliable vertices (see volume_estimate.h). Returns the
/// number of unreliable vertices. With a `piece`, collective: the median gradient is the whole
/// surface's (over every piece's own vertices).
std::size_t finish_volume_field(const Mesh& mesh, const VertexCorners& corners,
                                const RawVertex& raw, const ScaleLadder& ladder,
                                bool finer_scales, float ao_scale, CurvatureField& field,
                                const SurfacePiece* piece);

}  // namespace isocurv::curvature::detail
