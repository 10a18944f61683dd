#pragma once
// A scale-space pyramid over a volume, so that the volume estimator's smoothing costs about the
// same at any scale (curvature/volume_estimate.h).
//
// Level 0 is the volume itself. Level k + 1 is level k smoothed along each axis it decimates by
// the discrete Gaussian of variance kPyramidVariance (level k's index units; prefilter_taps),
// then sampled at every second index along those axes: level k + 1's index j is level k's 2 j
// there, the same world point (one origin; the spacing doubles). An axis is decimated while its
// spacing stays within the finest axis's spacing at that level, so a 1 x 1 x 3.5 grid keeps its
// slices until level 3; and while the level keeps at least kPyramidMinSamples samples across a
// dense volume. Each level's samples carry their own smoothing, `variance` per axis (its index
// units squared: v(k+1) = (v(k) + kPyramidVariance) / 4 where decimated), which the prefilter at
// that level leaves out (volume/prefilter.h, plan_smoothing's own_variance).
//
// An evaluation at world scale sigma reads level_for(sigma): the coarsest level where sigma is at
// least kPyramidVoxels of its spacing along every decimated axis, so its prefilter spans a few
// of the level's samples whatever sigma is, and the decimation's smoothing (at its new Nyquist
// frequency a 0.7% gain) has aliased nothing the rest of the smoothing keeps.
//
// Past a dense volume's box, level 0 repeats its nearest border sample (each pass clamps its own
// axis); the coarser levels are that extended field smoothed and sampled, past the box too. It
// is constant along an axis from the first sample whose decimation taps all lie past the finer
// level's box, so a coarser level's box (its frame's lo, hi) reaches that sample and its reads
// clamp there: exact, and a plan never asks for bricks further out. (Clamping at the samples
// 2 j inside the box instead would repeat a smoothed border sample that carries the interior
// outwards: a CT-like sphere 6 voxels from the box had H 0.52% at 5.6 voxels, 0.27% at level 0.)
// A sparse grid's inactive voxels read as its background at every level.
//
// Only the bricks asked for are built (build), each once, from the bricks of the level under it
// that it reads (built first): a surface's pyramid covers its surroundings, not the volume.
// Deterministic: a sample's value depends only on the volume, not on which bricks were asked for
// or in which order. Lifetime: keeps a reference to the volume's grid (it must outlive the
// pyramid and not change). Threading: build is serialised by a mutex; level() may be read while
// no build runs.
// Tested in tests/volume/test_pyramid.cpp.
#include <openvdb/openvdb.h>

#include <array>
#include <memory>
#include <mutex>
#include <unordered_set>
#include <vector>

#include "volume/gaussian_jet.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// The decimation's smoothing, variance in the finer level's index units squared (deviation 2:
/// one sample of the coarser level).
inline constexpr double kPyramidVariance = 4.0;
/// An evaluation at world scale sigma uses the coarsest level where sigma is at least this many
/// of the level's spacings along each decimated axis (its prefilter's own variance then at least
/// kPyramidVoxels^2 - kSplineVariance - 4/3 = 2.25 samples squared).
inline constexpr double kPyramidVoxels = 2.0;
/// A dense volume's axis is decimated only while the next level keeps this many samples across.
inline constexpr int kPyramidMinSamples = 8;
/// The most levels (a sparse grid has no domain to stop them).
inline constexpr int kPyramidMaxLevels = 12;

/// One level of a Pyramid.
struct PyramidLevel {
  openvdb::FloatGrid::Ptr grid;      ///< level 0: the volume's own; above, the bricks built so far
  GridFrame frame;                   ///< index -> world, and the level's domain when clamping
  openvdb::Vec3d variance{0, 0, 0};  ///< the samples' own smoothing, index units squared
  openvdb::Coord factor{1, 1, 1};    ///< level index j is level-0 index j * factor
  std::array<bool, 3> decimated{};   ///< which axes this level halved (none at level 0)
};

class Pyramid {
 public:
  /// The levels of `volume` (none built yet above level 0). Throws what grid_frame throws.
  explicit Pyramid(const Volume& volume);

  int levels() const { return int(levels_.size()); }
  const PyramidLevel& level(int k) const { return levels_[std::size_t(k)]; }
  /// The level an evaluation at world scale `sigma` reads (see above).
  int level_for(double sigma) const;
  /// The scale (world units) from which level k + 1 takes over from level k (infinity for the
  /// last level).
  double upper_scale(int k) const;
  /// The largest scale (world units) whose level's prefilter stays within
  /// kMaxPrefilterDeviation samples along every axis (volume/prefilter.h).
  double max_scale() const;

  /// Makes level k hold every sample of `bricks` (level k's brick coordinates, voxel / 8); level
  /// 0 holds them already. Parallel (TBB) over the bricks built.
  void build(int k, const std::vector<openvdb::Coord>& bricks);

  /// Bricks built above level 0 (for reports and tests).
  std::size_t built_bricks() const;

  /// Drops level 0's reference to the volume's grid (PyramidLease keeps a pyramid between calls
  /// without keeping its volume alive); rebind gives it back. Levels above 0 are kept.
  void unbind() { levels_[0].grid.reset(); }
  /// Level 0 reads `grid` again: the grid the pyramid was made of (the caller checks).
  void rebind(openvdb::FloatGrid::Ptr grid) { levels_[0].grid = std::move(grid); }
  /// The decimation's taps either side (kPyramidVariance's prefilter).
  int decimation_radius() const { return decimation_radius_; }

 private:
  struct CoordHash {
    std::size_t operator()(const openvdb::Coord& c) const;
  };
  /// The decimation's smoothing (prefilter_taps(kPyramidVariance)), computed once.
  std::vector<float> decimation_;
  int decimation_radius_ = 0;
  std::vector<PyramidLevel> levels_;
  std::vector<std::unordered_set<openvdb::Coord, CoordHash>> built_;
  std::mutex mutex_;
  void build_locked(int k, const std::vector<openvdb::Coord>& bricks);
};

/// Bricks a kept pyramid (PyramidLease) may hold between calls: 512 MiB of samples.
inline constexpr std::size_t kKeptPyramidBricks = (std::size_t(512) << 20) / (512 * sizeof(float));

/// A pyramid of `volume` for one estimate, kept between estimates on the same volume: the levels
/// above 0 are the smoothing that depends neither on the isovalue nor on the scale, so an
/// isovalue sweep (--iso a,b,c), several scales (--scale 1,2) or repeated calls from Python on one
/// volume build each coarse brick once. The lease takes the pyramid kept from the previous lease
/// of the same grid (volume.grid, the same domain), or makes a new one; when the lease ends the
/// pyramid is kept in its place (one pyramid for the whole process, the last volume's) unless it
/// holds more than kKeptPyramidBricks bricks. The kept pyramid holds no reference to the volume's
/// grid (level 0 is dropped, the grid only watched), so it never keeps a volume alive; it is
/// dropped at the next lease of another grid. Its memory is at most kKeptPyramidBricks bricks,
/// and in practice an eighth of the bricks around the surfaces asked for, and less (levels 1, 2,
/// ...: about 1/7 of them). The volume's values must not change while its grid lives (the
/// pyramid cannot see it). Threading: leases may be taken from several threads; two leases at
/// once on one volume get two pyramids (the second a new one).
class PyramidLease {
 public:
  explicit PyramidLease(const Volume& volume);
  ~PyramidLease();
  PyramidLease(const PyramidLease&) = delete;
  PyramidLease& operator=(const PyramidLease&) = delete;
  Pyramid& operator*() { return *pyramid_; }
  Pyramid* operator->() { return pyramid_.get(); }
  /// Whether the pyramid came from an earlier lease (for tests and reports).
  bool reused() const { return reused_; }

 private:
  std::unique_ptr<Pyramid> pyramid_;
  std::weak_ptr<const openvdb::FloatGrid> grid_;
  openvdb::CoordBBox domain_;
  bool reused_ = false;
};

/// How far (world units, along index axis `axis`) the level-0 samples that an evaluation at world
/// scale `sigma` depends on may lie from the point it was asked at, when the evaluation may move
/// `reach` world units from it: the prefilter's taps, the B-spline's and every decimation's, plus
/// a sample for rounding. It grows with sigma. For the ghost margins of a divided volume
/// (app/distributed.cpp).
double pyramid_support(const Pyramid& pyramid, double sigma, int axis, double reach);

}  // namespace isocurv::volume
