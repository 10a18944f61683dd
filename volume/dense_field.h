#pragma once
// A volume's samples over its data domain as one dense float array, with the trilinear field and
// gradient normals read from it, and the value range and slope of every 8^3-cell brick (the ray
// caster's empty-space skipping). What the device stages that sample the volume at arbitrary
// points upload (screen/ray_cast, features' sampled path); dense_field.cl is the same field on the
// device. Independent of the isovalue: built once, read at any number of isovalues.
#include <array>
#include <cstdint>
#include <vector>

#include "volume/volume.h"

namespace isocurv::volume {

/// Most samples a DenseField holds (1 GiB of floats); a larger data domain is an Error.
inline constexpr std::uint64_t kMaxFieldSamples = std::uint64_t(1) << 28;
/// Cells per brick edge of the skipping grid (the mesher's brick size, mc::kBrick).
inline constexpr int kFieldBrick = 8;
/// The widest smoothing DenseField::smooth takes (voxels): the prefilter's widest taps.
inline constexpr double kMaxSmoothingVoxels = 6.0;

/// DenseField::surface_bounds ignores groups of bricks under this fraction of the largest group.
inline constexpr double kSpeckBrickFraction = 0.01;

/// Index space here counts from the domain's first voxel: sample (i, j, k) is voxel
/// domain.min() + (i, j, k), at values[i + nx (j + ny k)].
struct DenseField {
  int nx = 0, ny = 0, nz = 0;  ///< samples per axis (each >= 2)
  std::vector<float> values;   ///< raw voxel values (non-finite ones read as outside)
  int bx = 0, by = 0, bz = 0;  ///< bricks per axis: ceil((n - 1) / kFieldBrick)
  /// Per brick (index bx_i + bx (by_i + by bz_i)): min and max of the finite samples it reads
  /// (its 9^3 corners, clipped to the domain); min > max when there are none.
  std::vector<std::array<float, 2>> brick_range;
  /// Per brick: the largest |difference| of two neighbouring samples (along one axis) it reads,
  /// a bound on every index-space partial derivative of the trilinear field inside the brick's
  /// box, so |d field / dt| <= brick_slope * |d|_1 along a ray p + t d there (the safe stride of
  /// the ray march). Infinity where the brick reads a non-finite sample; 0 for a constant one.
  std::vector<float> brick_slope;
  float sign = 1;  ///< +1: inside is above the isovalue; -1: below (Inside::Below)
  /// world = A index + b, row-major 3x4 (the grid's affine transform, from the domain's origin).
  std::array<double, 12> to_world{};
  std::array<double, 12> to_index{};  ///< its inverse
  /// The inverse transpose of A (index-space gradients to world-space ones), row-major 3x3.
  std::array<double, 9> normal_matrix{};
  std::array<double, 6> bounds{};  ///< world box of the domain (xmin, xmax, ymin, ymax, zmin, zmax)
  std::uint64_t id = 0;            ///< unique per construction (device caches key on it)

  /// Copies the samples of `v`'s data domain (dense: its domain; sparse: the active box) and
  /// ranks the bricks. Parallel (TBB), deterministic.
  /// @throw Error for an empty volume, a non-affine transform, a domain thinner than 2 samples
  /// on an axis, or more than kMaxFieldSamples samples
  explicit DenseField(const Volume& v);
  DenseField() = default;

  /// Smooths the samples in place by a separable sampled Gaussian of deviation `sigma` voxels
  /// along each index axis (volume::prefilter_taps: its discrete variance is exactly sigma^2;
  /// samples beyond the domain repeat its faces; non-finite samples stay as they are and are
  /// left out of their neighbours' sums), then ranks the bricks again and takes a new id (device
  /// caches upload it again). For quantised, noisy volumes: per-pixel normals of 8-bit steps are
  /// terraces at the pixel scale. The surface moves by about sigma^2 times its mean curvature
  /// (in voxels). sigma 0 leaves everything as it is. Parallel (TBB), deterministic.
  /// @throw Error for a sigma that is negative, not finite or above kMaxSmoothingVoxels
  void smooth(double sigma);

  /// Signed insideness sign * (value - iso) at sample (i, j, k): > 0 inside, <= 0 outside.
  /// Non-finite samples read -1 (outside).
  float signed_at(int i, int j, int k, float iso) const {
    const float v = values[std::size_t(i) + std::size_t(nx) * (j + std::size_t(ny) * k)];
    return std::isfinite(v) ? sign * (v - iso) : -1.0f;
  }
  /// Whether brick b may hold surface at `iso`: it has a sample inside and one outside.
  bool brick_straddles(std::size_t b, float iso) const {
    const auto& r = brick_range[b];
    if (!(r[0] <= r[1])) return false;
    return sign > 0 ? (r[1] > iso && r[0] <= iso) : (r[0] < iso && r[1] >= iso);
  }
  /// The trilinear signed field at index point p (clamped into the domain) and its index-space
  /// gradient (of the trilinear interpolant, the hit test's field).
  double field(const std::array<double, 3>& p, float iso,
               std::array<double, 3>* gradient = nullptr) const;
  /// The unit outward normal at index point p as gradient_normals computes it: central
  /// differences at the samples (one-sided at the border), trilinearly interpolated, carried to
  /// world space by normal_matrix, pointing to decreasing insideness. Zero for a zero gradient.
  std::array<double, 3> normal(const std::array<double, 3>& p) const;
  std::array<double, 3> world(const std::array<double, 3>& index) const;
  /// to_index (12), to_world (12) and normal_matrix (9) in float, then 3 zeros: the transform
  /// buffer dense_field.cl's affine() and linear3() read (to_index at 0, normal_matrix at 24).
  std::array<float, 36> device_transform() const;
  /// The shortest voxel edge in world units (the smallest column norm of the index -> world map).
  double shortest_voxel_edge() const;
  /// The world box (xmin, xmax, ymin, ymax, zmin, zmax) of the bricks that straddle `iso` (a
  /// box around the isosurface, within a brick of it), or false when none does (no surface).
  /// Specks are left out, as core/framing_points leaves them out of a mesh's box: groups of
  /// straddling bricks (26-connected) with under kSpeckBrickFraction of the largest group's
  /// bricks (noise blobs far from a CT's object would otherwise shrink it in the picture).
  bool surface_bounds(float iso, std::array<double, 6>& box) const;
  std::array<double, 3> index(const std::array<double, 3>& world) const;

 private:
  /// brick_range and brick_slope from the samples.
  void rank_bricks();

 public:
  /// The index-space box [box[0], box[1]] x [box[2], box[3]] x [box[4], box[5]] (samples) of
  /// every brick that straddles `iso`, specks included: each crossing of the trilinear field lies
  /// in it, and outside it the field keeps one sign along any path (neighbouring bricks share
  /// their face samples). False when no brick straddles (no surface).
  bool straddling_box(float iso, std::array<int, 6>& box) const;
};

}  // namespace isocurv::volume
