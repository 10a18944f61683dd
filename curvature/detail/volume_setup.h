#pragma once
// Internals the volume estimator's device path and its reference share
// (curvature/volume_estimate.h), implemented in volume_setup.cpp.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
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
#include "volume/prefilter.h"
#include "volume/pyramid.h"
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
  /// `frame` is a pyramid level's (volume/pyramid.h): its samples' own smoothing, index units
  /// squared per axis, which the prefilter leaves out (zero at level 0).
  openvdb::Vec3d own_variance{0, 0, 0};
  /// The largest scale the volume's pyramid serves, world units (volume::Pyramid::max_scale).
  double max_scale = 0;
};

/// `setup` at another scale.
inline VolumeSetup with_sigma(VolumeSetup setup, double sigma) {
  setup.sigma = sigma;
  return setup;
}

/// `setup` on level k of `pyramid`: its frame and own smoothing; the scale, the voxel (level
/// 0's largest spacing, which the staircase and the Newton move are measured in) and the rest
/// unchanged.
inline VolumeSetup on_level(VolumeSetup setup, const volume::Pyramid& pyramid, int k) {
  setup.frame = pyramid.level(k).frame;
  setup.own_variance = pyramid.level(k).variance;
  return setup;
}

/// Checks the mesh, options.sigma, options.ao_scale and the grid (see volume_estimate) and derives
/// the setup, with options.point resolved (resolved_point).
VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume,
                         const VolumeOptions& options);

/// The smoothing plan of an evaluation at setup.sigma for `positions`: setup's frame (a pyramid
/// level's after on_level), the reach of spline_reach and the samples' own variance.
volume::SmoothingPlan plan_of(const Positions& positions, const VolumeSetup& setup);

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

/// The two pilot scales of the per-vertex choice, world units (p1 < p2).
struct PilotScales {
  double p1 = 0, p2 = 0;
};
/// The pilots over s1 (setup.sigma, the scale the noise alone asks for). Grey levels: at
/// kGreyPilots[0] and kGreyPilots[1] times s1. The bias is measured from their difference, and
/// at s1 the noise hid it: the difference grows as the scales squared and the noise falls as
/// their power 3.5 (bench_accuracy --refine's torus at 2x: at s1 and 2 s1 its bias stood out
/// nowhere, every vertex took the largest scale, and the error was 1.8x that at 1x; at 2 s1 and
/// 4 s1 it is 0.8x). Binary volumes: s1 and kBinaryPilot s1 (their scale comes from the first
/// pilot's shape, see NoiseModel::staircase).
inline constexpr double kGreyPilots[2] = {2.0, 4.0};
inline constexpr double kBinaryPilot = 2.0;
/// Grey levels: no scale above the second pilot's. The bias the pilots measure is local and
/// quadratic; far past them it is neither (a rounded box's flat faces, L = 0, took 12 voxels and
/// smeared the edges' curvature into them: its integral of H 1.1% short).
inline constexpr double kExtrapolation = 1.0;

/// The pilots for a first scale `s1`, within the choice's largest scale, or nothing when that
/// leaves no room above s1 (then every vertex keeps s1).
inline std::optional<PilotScales> pilot_scales(const AdaptiveScale& adaptive, double s1) {
  if (adaptive.model.staircase) {
    const double p2 = std::min(kBinaryPilot * s1, adaptive.hi);
    return p2 > s1 ? std::optional<PilotScales>({s1, p2}) : std::nullopt;
  }
  const double p2 = std::min(kGreyPilots[1] * s1, adaptive.hi);
  const double p1 = std::max(s1, p2 * kGreyPilots[0] / kGreyPilots[1]);
  return p2 > p1 ? std::optional<PilotScales>({p1, p2}) : std::nullopt;
}
/// The second pilot evaluates one vertex in about this many (pilot_sample): its values only
/// enter region averages over hundreds of vertices, and the first pilot's noise is correlated
/// over 4 pi p1^2, some 200 vertices at p1 = 3.5 voxels.
inline constexpr unsigned kPilotStride = 8;
/// Whether the second pilot evaluates the vertex at `x`: a hash of its coordinates' bits, so the
/// same vertices whatever their order (a distributed piece's are ordered differently).
inline bool pilot_sample(const Vec3f& x) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (float c : x) {
    std::uint32_t bits;
    std::memcpy(&bits, &c, sizeof bits);
    h = (h ^ bits) * 0xff51afd7ed558ccdull;
    h ^= h >> 33;
  }
  return h % kPilotStride == 0;
}
/// Grey levels: no scale under the first pilot's over this. Under it the noise model still holds
/// but the reconstruction of the blurred edge from its samples biases H (a rounded box at 1 to
/// 1.6 voxels: its integral of H 1.1% short, at 2.3 voxels 0.2%), which the pilots do not see.
inline constexpr double kUnderPilot = 1.41421356237309515;

/// Evaluates every vertex of `mesh` at setup.sigma; with `adaptive`, at the two pilot scales
/// instead (pilot_scales), gives each vertex the scale choose_vertex_scales finds from the two,
/// and evaluates it there. Then, when `finer_scales`, the vertices their scale does not fit (eroded or opposed:
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
