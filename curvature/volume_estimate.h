#pragma once
// The volume estimator: curvature of the volume itself at each mesh vertex, from derivatives of
// the volume reconstructed at scale sigma: the samples smoothed once by a separable Gaussian
// prefilter (volume/prefilter.h), then a quartic B-spline through them (volume/spline_jet.h),
// together a smoothing of variance sigma^2 in world space.
//
// At each vertex x the estimator takes the jet (value, gradient, Hessian, third derivatives) of
// the reconstructed field at x itself and gives the curvature of the field's level set through x
// by curvature/implicit_curvature.h (Normals, k1 >= k2, dir1, dir2, H, K, dcurv, ShapeIndex,
// Curvedness, AO). Not the smoothed field's isovalue surface: smoothing moves level sets inward
// roughly like mean-curvature flow (by about sigma^2 H), so that surface shrinks thin parts and
// loses them, while the level set through the vertex keeps the vertex's own radius (a sphere's or
// a tube's level sets stay concentric; bench_accuracy: a tube of radius 3.5 voxels at 2 voxels,
// H 13% on the smoothed isosurface, 2% here). Area and Boundary come from the mesh
// (curvature/mesh_areas.h).
//
// The scale per vertex: each vertex is measured at sigma unless the scale does not fit it there,
// then at sigma / kScaleStep, and so on down to the floor (kFloorVoxels); it
// keeps the first scale that fits (the "Scale" array, world units). A scale does not fit when
//  - the smoothed field's isosurface lies more than kMaxShiftScales * sigma from the vertex
//    (eroded: for a sphere or tube of radius r that happens above sigma ~ r or 2 r, so thin
//    parts keep a scale they survive, while flat parts keep the large noise-driven one; at half
//    a deviation the lobster sent 63% of its vertices finer instead of 41%, for no gain on
//    bench_accuracy's classes),
//  - the smoothed gradient points against the mesh's normal (opposed: two surfaces closer than
//    the scale merged).
// At the floor a vertex keeps the floor's values; one still opposed there is measured once more
// at the reconstruction's own limit (volume::kMinScaleVoxels of the largest spacing), and if
// still opposed takes the level set through it oriented as the mesh says (normal and curvature
// signs flipped): a thin gap or sheet's wall, seen through its neighbour.
//
// The box: outside a dense volume the samples repeat the nearest border sample (clamping, each
// pass along its own axis), so no false edge appears where the data stops, and a closed surface
// near the box is measured as anywhere else. Where the surface is cut by the box, that extension
// continues it straight across the cut, which biases what the smoothing sees: vertices within
// kSupportDeviations deviations of the cut (the mesh's open boundary; detail::CutIndex) are
// flagged Boundary. Their scale is not reduced: at finer scales the noise costs more than the
// extension (bench_accuracy, sphere cut by the box).
//
// A vertex is Unreliable (flag 1, its curvature zero, AO that of a plane, its
// normal the area-weighted face normal) where the gradient is at most
// volume::kWeakGradientFraction of its median over the vertices (with finer scales off, also
// where the scale does not fit it).
//
// Cost follows the surface: only the 8^3 bricks the vertices' B-splines read, and what the
// prefilter's three passes need for them, are gathered and filtered; a vertex then reads 5^3
// smoothed samples, whatever the scale. Scales of kPyramidVoxels (2) samples of a coarser level
// of the volume's scale-space pyramid (volume/pyramid.h: 4 voxels and more on level 1, 8 on
// level 2, ...) are evaluated there, so a scale of 20 voxels filters about as many samples with
// as many taps as one of 3, and scales have no ceiling but the volume's size.
// Tested in tests/curvature/volume_estimate_test.cpp, tests/curvature/volume_piece_test.cpp.
#include <cstddef>
#include <optional>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "core/surface_piece.h"
#include "curvature/adaptive_scale.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"
#include "volume/volume.h"

namespace isocurv::curvature {

/// VolumePoint::surface: the smoothing's shrinkage at a point of the smoothed isosurface of mean
/// curvature H, with y = sigma^2 H^2: sigma^2 H (1 - kSurfaceY1 y + kSurfaceY2 y^2) (the factor at
/// least 1/2). The surface point (CurvatureField::surface_points) lies that far out along the
/// normal, and the curvatures are that parallel surface's (k / (1 + e k)). Fitted on the exact
/// shifts of Gaussian-smoothed balls and cylinders (Gaussian probabilities of a ball and a disc):
/// within 0.002 sigma up to sigma / r = 1/2 for balls and 0.006 sigma up to 0.6 for cylinders,
/// the per-vertex scale's reach (kBinaryShapeScale); the first-order sigma^2 H (1 - y / 3) it
/// replaces was 0.036 sigma short on a ball at 1/2 (a binary ball measured 2.6% short in volume).
inline constexpr double kSurfaceY1 = 0.31, kSurfaceY2 = 0.117;
/// VolumePoint::surface: a scale does not fit a vertex (as if eroded) where a principal
/// curvature's correction factor 1 + e k falls under this: the smoothed surface there is no
/// parallel surface of the real one (binary spheres at sigma / r near 1/2 had vertices where
/// the factor fell to 0.1 and H to -13 / r).
inline constexpr double kMinCorrection = 0.5;
/// VolumePoint::surface: Newton steps along the gradient line, and the largest move in voxels.
inline constexpr int kNewtonSteps = 3;
inline constexpr double kMaxShiftVoxels = 1.5;

/// A scale is too large for a vertex when the smoothed field's isosurface lies more than this many
/// deviations from it (see above).
inline constexpr double kMaxShiftScales = 1.0;
/// The ratio of one scale of the per-vertex choice to the next finer one.
inline constexpr double kScaleStep = 1.41421356237309515;
/// The finest scale of the per-vertex choice, in voxels (the geometric mean spacing; never under
/// volume::kMinScaleVoxels of the largest), unless the asked scale is finer: at 0.8 voxel the reconstruction does not alias (bench_accuracy: float sphere
/// H 0.03%) and 8-bit noise is still bounded.
inline constexpr double kFloorVoxels = 0.8;
/// The smoothing's support, in deviations, for the box test (95% of a Gaussian's weight).
inline constexpr double kSupportDeviations = 2.0;

/// Wall time of the volume estimator's steps in ms (device path, summed over the finer scales;
/// the queue is drained between steps): planning the bricks, gathering the samples, the
/// prefilter's passes (with the padded copy), the per-vertex kernel with the downloads, and the
/// host's Area, Boundary and Unreliable pass.
struct VolumeStepTimes {
  double plan = 0, gather = 0, smooth = 0, vertices = 0, finish = 0;
};

/// What one volume estimate did.
struct VolumeEstimateStats {
  std::size_t unreliable = 0;  ///< vertices flagged Unreliable
  std::size_t bricks = 0;      ///< 8^3 bricks filtered or gathered (device path), all scales
  std::size_t finer_scale = 0;  ///< vertices the guard measured finer than first given
  std::size_t outside = 0;      ///< vertices whose support leaves the box at their scale
  double blur = 0;              ///< adaptive: the edge blur the choice measured, world units
  VolumeStepTimes steps;        ///< device path only
  /// Pyramid bricks above level 0 already built when the call began: kept from an earlier
  /// estimate on the same volume (volume::PyramidLease), 0 for a new pyramid.
  std::size_t pyramid_kept = 0;
};

/// How volume_estimate measures.
struct VolumeOptions {
  /// World units: the scale every vertex starts at (with `adaptive`, the first pilot's).
  double sigma = 0;
  float ao_scale = 1;  ///< Options::ao_scale
  /// The per-vertex guard above (the default). Off, every vertex is measured at sigma and those
  /// the scale does not fit (eroded or opposed) are Unreliable (the multi-scale arrays use that,
  /// so that each scale shows only what it resolves); the Scale array is then absent, and
  /// `adaptive` is ignored.
  bool finer_scales = true;
  /// Where each vertex's curvature is taken (curvature/options.h, VolumePoint); automatic (the
  /// default): resolved_point's choice.
  VolumePoint point = VolumePoint::automatic;
  /// The per-vertex scale from the data and the shape (curvature/adaptive_scale.h; the default
  /// of estimate_field): the noise model of the volume. Absent: every vertex starts at sigma.
  std::optional<NoiseModel> adaptive;
  /// adaptive: the largest scale, world units; 0: kAdaptiveMaxVoxels voxels (the geometric mean
  /// spacing), within the volume and the pyramid's volume::Pyramid::max_scale.
  double adaptive_max = 0;
  /// `mesh` is one piece of a surface divided among processes (core/surface_piece.h), extracted
  /// with a margin wide enough for the smoothing of its own vertices at the largest scale (the
  /// scale's kPrefilterRadius deviations plus the B-spline's reach) and for the box test; the
  /// call is collective, and the piece's own vertices get bit-identical values to the single
  /// process's on the whole surface (the whole-surface quantities, the median gradients, are
  /// reduced). nullptr: the whole surface.
  const SurfacePiece* piece = nullptr;
};

/// The volume estimator on `device` (float; the same steps as volume_estimate_reference) for the
/// surface at `isovalue` of `volume` from which `mesh` was extracted: one CurvatureField entry per
/// mesh vertex, world units (curvatures in 1 / world units, Scale in world units), normals outward
/// (volume.inside). Only the bricks the vertices need are gathered and sent to the device, where
/// the passes of curvature/detail/volume_passes.h run (plan, gather, smooth, pad, evaluate, read
/// back) once per scale of the per-vertex choice.
/// Deterministic: the same inputs give the same bits at every work-group size and on every piece
/// of a distributed surface (options.piece).
/// Threading: calls on one device are serialised (one mutex per device); calls on different
/// devices may run in parallel. `stats` (optional) receives what the call did.
/// Errors (isocurv::Error, nothing written to `stats`): options.sigma not positive and finite,
/// larger than the volume, under volume::kMinScaleVoxels voxels of the coarsest axis, or above
/// volume::Pyramid::max_scale (a thin side of the volume); ao_scale not
/// finite; a grid transform that is not affine with orthogonal axes; an invalid mesh
/// (check_input); an OpenCL failure (core/device_call.h: the queue is drained first).
CurvatureField volume_estimate(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                               const VolumeOptions& options, Device& device,
                               VolumeEstimateStats* stats = nullptr);

/// VolumeOptions at a fixed scale `sigma` (without `adaptive`); the other fields keep their
/// defaults.
inline VolumeOptions fixed_scale(double sigma, float ao_scale = 1) {
  VolumeOptions o;
  o.sigma = sigma, o.ao_scale = ao_scale;
  return o;
}

/// VolumePoint::automatic resolved for `volume`: surface on binary volumes (curvature::is_binary:
/// their vertices sit on the voxel staircase), vertex otherwise; other values unchanged.
VolumePoint resolved_point(VolumePoint point, const volume::Volume& volume);

/// VolumePoint::vertex: the surface points (CurvatureField::surface_points) of `mesh`'s
/// marching-cubes vertices on `volume`'s grid, from the curvature in `field` (normals, k1, k2,
/// dir1, dir2). Marching cubes places a vertex where the linear interpolation along its cube edge
/// (grid axis a, length h, the vertex at s in [0, 1]) crosses the isovalue; on a curved surface the
/// field along the edge is not linear: with the surface's normal curvature kappa along the edge
/// e (k1 (e.dir1)^2 + k2 (e.dir2)^2) and c = n.e, the crossing lies (kappa h^2 / 2 c) s (1 - s)
/// further along e (second order; the ratio kappa h / 2 c kept within 1/2, for edges nearly
/// along the surface). It assumes the field's second derivative across the surface vanishes at
/// the isovalue, as for distance fields and for blurred edges cut at half height (CT at the
/// midpoint of two materials). Vertices not on a grid edge (snapped, or with all three index
/// coordinates whole) and Unreliable ones keep their position. A float torus of tube radius 6
/// on a 1 x 1 x 2.5 grid: its vertices lie 0.021 units inside the surface on average, and the
/// volume measured over them is 0.82% short, over the surface points 0.04%.
std::vector<Vec3f> edge_surface_points(const Mesh& mesh, const volume::Volume& volume,
                                       const CurvatureField& field);

/// The specification: the same in double precision on the host (volume::smooth_reference and
/// volume::spline_jet), parallel over vertex batches (TBB).
CurvatureField volume_estimate_reference(const Mesh& mesh, const volume::Volume& volume,
                                         float isovalue, const VolumeOptions& options,
                                         VolumeEstimateStats* stats = nullptr);

}  // namespace isocurv::curvature
