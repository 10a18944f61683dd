#pragma once
// The volume smoothed at a scale, on the bricks a set of points need: the first half of the volume
// estimator's reconstruction (the second is volume/spline_jet.h).
//
// The reconstructed field at scale sigma (world units) is F(q) = sum_i S_i beta4(q - i) in index
// coordinates q, where beta4 is the centred quartic B-spline (per axis, a tensor product) and S the
// samples smoothed by a separable Gaussian whose variance along axis a is
// (sigma / spacing_a)^2 - kSplineVariance: the B-spline adds the rest, so F is the samples
// smoothed by a kernel of variance (sigma / spacing_a)^2 along each axis, which matches a Gaussian
// of deviation sigma in all moments up to the third (to the fourth within 1/24 voxel^4). Filtering
// once per voxel instead of per evaluation point is what makes the estimator cheap: a point then
// reads 5^3 smoothed samples instead of (10 sigma + 1)^3 raw ones.
//
// Samples outside a dense volume's domain repeat the nearest domain sample (each pass clamps its
// own axis, which is the same thing since the filters are separable); a sparse grid's inactive
// voxels read as its background. Nothing here is sized by the dense volume: only the bricks the
// points' reconstruction reads, and what the passes need for them, are filtered.
// Tested in tests/volume/test_prefilter.cpp.
#include <openvdb/openvdb.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "volume/gaussian_jet.h"

namespace isocurv::volume {

/// Variance of the centred quartic B-spline (index units squared): the reconstruction's own
/// smoothing, which the prefilter leaves out.
inline constexpr double kSplineVariance = 5.0 / 12.0;

/// The smallest scale, in voxels of the coarsest axis, that the reconstruction can represent
/// (sqrt(kSplineVariance) = 0.645 rounded up): below it the B-spline alone smooths too much.
inline constexpr double kMinScaleVoxels = 0.65;

/// Half-width of the B-spline's support (taps floor(q - 1.5) .. floor(q + 2.5)).
inline constexpr double kSplineReach = 2.5;

/// The prefilter's taps reach this many of its deviations: its variance is matched exactly
/// whatever the truncation (below), so this only trims its fourth moment (bench_accuracy's errors
/// at 3 and at 4 deviations agree to 2-3 digits; 3 needs a quarter fewer taps at 2 voxels).
inline constexpr double kPrefilterRadius = 3.0;
/// The largest scale one prefilter takes, in samples of its grid. The volume estimator reaches
/// larger scales on coarser levels of a pyramid (volume/pyramid.h), where a scale spans a few
/// samples whatever its size.
inline constexpr double kMaxPrefilterDeviation = 16.0;
/// The most taps either side of a prefilter: kPrefilterRadius times kMaxPrefilterDeviation.
inline constexpr int kPrefilterMaxRadius = 48;

/// One axis's prefilter: taps -radius .. radius, weight w[t + radius], summing to 1. A sampled
/// Gaussian truncated at kPrefilterRadius of its deviation, the deviation chosen so that the
/// weights' discrete variance is exactly `variance` (they differ by under 1e-5 for deviations
/// above 0.8; below, a sampled Gaussian's variance falls short of its parameter's square).
struct PrefilterTaps {
  int radius = 0;
  std::vector<double> w{1.0};
};

/// The prefilter for `variance` (index units squared; 0 gives the identity, one tap).
/// @throw isocurv::Error when variance is negative or not finite.
PrefilterTaps prefilter_taps(double variance);

/// A set of 8^3 bricks: their brick coordinates (voxel / 8, floor) in a fixed order, and a dense
/// table over the plan's region giving each region brick's number in that order (-1: not in the
/// set).
struct BrickSet {
  std::vector<openvdb::Coord> bricks;
  std::vector<std::int32_t> table;
};

/// The three separable passes' brick sets. stages[0]: the samples the pass along x reads;
/// stages[1]: that pass's output, which the pass along y reads; stages[2]: the y pass's output;
/// stages[3]: the z pass's output, the smoothed samples S (every tap of every point's B-spline,
/// anywhere within `reach` of it). Each stage holds exactly the bricks the next pass reads.
struct SmoothingPlan {
  GridFrame frame;
  std::array<PrefilterTaps, 3> taps;  ///< the prefilter along each index axis
  openvdb::Coord origin{0, 0, 0};     ///< the region's first brick (brick coordinates)
  openvdb::Coord dims{0, 0, 0};       ///< the region's size in bricks
  std::array<BrickSet, 4> stages;

  /// The index into a stage's table of brick `b` (brick coordinates), which must be in_region.
  std::size_t cell(const openvdb::Coord& b) const {
    const openvdb::Coord r = b - origin;
    return (std::size_t(r[2]) * dims[1] + r[1]) * dims[0] + r[0];
  }
  /// The index of voxel `voxel` (index coordinates) in the samples of `set` (one of stages, 512
  /// per brick in the set's order, x fastest within a brick), or -1 when no brick of the set
  /// holds it.
  std::ptrdiff_t sample_index(const BrickSet& set, const openvdb::Coord& voxel) const;
  bool in_region(const openvdb::Coord& b) const {
    const openvdb::Coord r = b - origin;
    return r[0] >= 0 && r[1] >= 0 && r[2] >= 0 && r[0] < dims[0] && r[1] < dims[1] &&
           r[2] < dims[2];
  }
};

/// Plans the smoothing at world deviation `sigma` for B-spline evaluations anywhere within
/// `reach` (index units per axis, beyond the spline's own kSplineReach) of the index position of
/// each world point. `own_variance`: the smoothing the samples carry already (index units
/// squared per axis; a pyramid level's, volume/pyramid.h), which the prefilter leaves out.
/// Parallel (TBB), deterministic.
/// @throw isocurv::Error when sigma is below kMinScaleVoxels along an axis (or under what the
/// B-spline and own_variance smooth), above kMaxPrefilterDeviation, or the region's table would
/// exceed 2^31 bricks.
SmoothingPlan plan_smoothing(const GridFrame& frame, const Positions& world_points,
                             const openvdb::Vec3d& reach, double sigma,
                             const openvdb::Vec3d& own_variance = openvdb::Vec3d(0, 0, 0));

/// The samples of stages[0]'s bricks (512 per brick, voxel (x, y, z) of a brick at
/// (z * 8 + y) * 8 + x): the grid's values, at coordinates clamped to the domain for a dense
/// volume. Parallel (TBB).
std::vector<float> gather_stage_samples(const openvdb::FloatGrid& grid, const SmoothingPlan& plan);

/// The same for any list of bricks (brick coordinates) on `frame`'s grid, appended to `out` in
/// the list's order. Parallel (TBB).
void gather_bricks(const openvdb::FloatGrid& grid, const GridFrame& frame,
                   const std::vector<openvdb::Coord>& bricks, std::vector<float>& out);

/// The smoothed samples S on stages[3]'s bricks, in double precision: the specification of the
/// device passes (curvature/volume_kernels.cl, smooth_axis). `background` is what a read outside
/// every brick returns (a valid plan never makes one).
struct SmoothedSamples {
  const SmoothingPlan* plan = nullptr;  ///< not owned; must outlive this
  std::vector<double> samples;          ///< 512 per brick of plan->stages[3]
  double background = 0;
};

/// Runs the three passes on the host in double precision. Parallel (TBB), deterministic.
SmoothedSamples smooth_reference(const openvdb::FloatGrid& grid, const SmoothingPlan& plan);

}  // namespace isocurv::volume
