#pragma once
// Internals the volume estimator's device path and its reference share
// (curvature/volume_estimate.h).
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/mesh.h"
#include "core/surface_piece.h"
#include "curvature/adaptive_scale.h"
#include "curvature/curvature_field.h"
#include "curvature/vertex_corners.h"
#include "curvature/volume_estimate.h"
#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::curvature::detail {

/// See VolumeSetup::max_shift.
inline constexpr double kShrinkScales = 0.5;

/// The checked inputs of one volume estimate.
struct VolumeSetup {
  volume::GridFrame frame;
  double sigma = 0;  ///< world units
  double voxel = 0;  ///< the largest spacing, world units
  double floor = 0;  ///< the finest scale of the per-vertex choice: min(sigma, kFloorVoxels voxel)
  /// VolumePoint::surface: the largest move to the smoothed isosurface, world units:
  /// kMaxShiftVoxels voxels plus kShrinkScales sigma (the smoothing shrinks a surface by about
  /// sigma^2 H, under 0.4 sigma where sigma kappa <= kBinaryShapeScale).
  double max_shift() const { return kMaxShiftVoxels * voxel + kShrinkScales * sigma; }
  VolumePoint point = VolumePoint::vertex;
  volume::Inside inside = volume::Inside::Above;
};

/// Checks mesh, sigma and the grid (see volume_estimate) and derives the setup.
VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume, double sigma);

/// How far from a vertex (index units per axis, beyond the B-spline's own support) the estimator
/// may evaluate the field: half a voxel, for rounding, plus (VolumePoint::surface) the Newton
/// steps' largest move, max_shift().
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
  std::size_t refined = 0;            ///< vertices measured finer than first given
  double blur = 0;                    ///< adaptive: the edge blur the choice measured, world units
};

/// The adaptive per-vertex scale (curvature/adaptive_scale.h): its noise model, its largest
/// scale (world units) and the piece the surface is divided into (or nullptr).
struct AdaptiveScale {
  NoiseModel model;
  double hi = 0;
  const SurfacePiece* piece = nullptr;
  /// A volume whose border samples vary (more than kFlatBorderNoise times its noise): the
  /// clamping (or a sparse grid's background) outside its box is then no continuation of the
  /// field (a distance field's slope stops there), so no vertex takes a scale above its distance
  /// to the box over kBorderDeviations (or the first pilot, if larger). A flat border (a
  /// scan's air, a mask's zeros) repeats what the volume would have held, and costs nothing.
  bool border_varies = false;
  openvdb::CoordBBox box;  ///< the volume's domain (index space), for border_varies
};
/// See AdaptiveScale::border_varies (and 0.1% of the value range, for noiseless fields).
inline constexpr double kFlatBorderNoise = 3.0;
/// See AdaptiveScale::border_varies: a slope that stops at the box, d deviations away, bends the
/// smoothed field's second derivatives by about G(d) / sigma; at 3 deviations that was 5% of H on
/// a distance-field sphere 6 voxels from the box, at 5 it is under 0.01%.
inline constexpr double kBorderDeviations = 5.0;
/// The adaptive choice `options` ask for on `volume` (its largest scale within the volume and the
/// prefilter's range), or nothing when they ask for none, or when that largest scale is not above
/// the first pilot's.
std::optional<AdaptiveScale> adaptive_of(const VolumeOptions& options, const VolumeSetup& setup,
                                         const volume::Volume& volume);

/// Per vertex of `mesh`: its distance to `box` (index space, on `frame`'s grid) over
/// kBorderDeviations, world units, and at least `least` (the first pilot: the scale the
/// noise alone asks for; see AdaptiveScale::border_varies).
std::vector<float> box_limits(const Mesh& mesh, const volume::GridFrame& frame,
                              const openvdb::CoordBBox& box, double least);

/// The second pilot's scale over the first's (the first is setup.sigma).
inline constexpr double kPilotRatio = 2.0;

/// The second pilot's scale for a first pilot `s1`, or nothing when the choice's largest scale
/// leaves no room above s1 (then every vertex keeps s1).
inline std::optional<double> second_pilot(const AdaptiveScale& adaptive, double s1) {
  const double s2 = std::min(kPilotRatio * s1, adaptive.hi);
  return s2 > s1 ? std::optional<double>(s2) : std::nullopt;
}
/// Grey levels: no scale above this many times the second pilot's. The bias the pilots measure
/// is local and quadratic; far past them it is neither (a rounded box's flat faces, L = 0,
/// took 12 voxels and smeared the edges' curvature into them: its integral of H 1.1% short).
inline constexpr double kExtrapolation = 2.0;
/// Grey levels: no scale under the first pilot's over this. Under it the noise model still holds
/// but the reconstruction of the blurred edge from its samples biases H (a rounded box at 1 to
/// 1.6 voxels: its integral of H 1.1% short, at 2.3 voxels 0.2%), which the pilots do not see.
inline constexpr double kUnderPilot = 1.41421356237309515;

/// Evaluates every vertex of `mesh` at setup.sigma; with `adaptive`, also at kPilotRatio times
/// that, gives each vertex the scale choose_vertex_scales finds from the two, and evaluates it
/// there. Then, when `finer_scales`, the vertices their scale does not fit (eroded or opposed:
/// volume_estimate.h) again at their scale / kScaleStep, and so on down to setup.floor, each
/// keeping the first scale it fits (or the floor's values). Without finer_scales, `adaptive` is
/// ignored.
VolumeEvaluation evaluate_with_finer_scales(const Mesh& mesh, const VertexCorners& corners,
                                            VolumeSetup setup, bool finer_scales,
                                            const VolumeEvaluate& evaluate, ScaleLadder& ladder,
                                            const AdaptiveScale* adaptive = nullptr);

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
