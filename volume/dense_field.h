#pragma once
// A volume's samples over its data domain as one dense float array, with the trilinear field and
// gradient normals read from it, and the value range and slope of every 8^3-cell brick (the ray
// caster's empty-space skipping). What the device stages that sample the volume at arbitrary
// points upload (screen/ray_cast, features' sampled path); dense_field.cl is the same field on the
// device. Independent of the isovalue: built once, read at any number of isovalues.
// Tested in tests/volume/test_dense_field_smooth.cpp, tests/screen/scenes.h.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "volume/volume.h"

namespace isocurv::volume {

/// Most samples a DenseField stores (1 GiB of floats): a dense box up to this many, or, for a
/// larger box of a sparse volume (.vdb), this many in its stored 8^3 tiles.
inline constexpr std::uint64_t kMaxFieldSamples = std::uint64_t(1) << 28;
/// Samples per edge of a sparse field's tiles (OpenVDB's leaf nodes).
inline constexpr int kFieldTile = 8;
/// Most tiles a sparse field's box may hold (2^24: a 2048^3 box); its tables and brick ranks
/// take about 20 bytes a tile.
inline constexpr std::uint64_t kMaxFieldTiles = std::uint64_t(1) << 24;
/// Cells per brick edge of the skipping grid (the mesher's brick size, mc::kBrick).
inline constexpr int kFieldBrick = 8;
/// The widest smoothing DenseField::smooth takes (voxels): the prefilter's widest taps.
inline constexpr double kMaxSmoothingVoxels = 6.0;

/// DenseField::surface_bounds ignores groups of bricks under this fraction of the largest group.
inline constexpr double kSpeckBrickFraction = 0.01;

/// Index space here counts from the domain's first voxel: sample (i, j, k) is voxel
/// domain.min() + (i, j, k). Two layouts of `values`, read through sample():
/// - dense: sample (i, j, k) at values[i + nx (j + ny k)];
/// - sparse (a .vdb whose active box holds more than kMaxFieldSamples voxels): the box is
///   aligned to OpenVDB's 8^3 leaves and cut in tiles of kFieldTile^3 samples, T of them
///   (tiles_x tiles_y tiles_z); values[t] holds tile t's slot (an int's bits, -1: no storage),
///   values[T + t] the constant value of a tile without storage (a VDB tile or the background),
///   and slot s's samples follow at values[2 T + 512 s + (i%8) + 8 ((j%8) + 8 (k%8))]: only the
///   leaves are stored, as the mesher's brick index keeps them. dense_field.cl reads both.
struct DenseField {
  int nx = 0, ny = 0, nz = 0;  ///< samples per axis (each >= 2)
  std::vector<float> values;   ///< raw voxel values (non-finite ones read as outside)
  bool sparse = false;         ///< the tiled layout above
  int tiles_x = 0, tiles_y = 0, tiles_z = 0;  ///< sparse: tiles per axis (ceil(n / 8))
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

  /// Copies the samples of `v`'s data domain (dense: its domain; sparse: the active box, in the
  /// tiled layout when it holds more than kMaxFieldSamples voxels) and ranks the bricks.
  /// Parallel (TBB), deterministic.
  /// @throw Error for an empty volume, a non-affine transform, a domain thinner than 2 samples
  /// on an axis, a dense domain of more than kMaxFieldSamples samples, or a sparse one whose
  /// leaves hold more
  explicit DenseField(const Volume& v);
  DenseField() = default;

  /// Smooths the samples in place by a separable sampled Gaussian of deviation `sigma` voxels
  /// along each index axis (volume::prefilter_taps: its discrete variance is exactly sigma^2;
  /// samples beyond the domain repeat its faces; non-finite samples stay as they are and are
  /// left out of their neighbours' sums), then ranks the bricks again and takes a new id (device
  /// caches upload it again); a sparse field refuses (Error). For quantised, noisy volumes: per-pixel normals of 8-bit steps are
  /// terraces at the pixel scale. The surface moves by about sigma^2 times its mean curvature
  /// (in voxels). sigma 0 leaves everything as it is. Parallel (TBB), deterministic.
  /// @throw Error for a sigma that is negative, not finite or above kMaxSmoothingVoxels
  void smooth(double sigma);

  /// The raw value of sample (i, j, k), 0 <= i < nx, ... (either layout).
  float sample(int i, int j, int k) const {
    if (!sparse) return values[std::size_t(i) + std::size_t(nx) * (j + std::size_t(ny) * k)];
    const std::size_t tiles = std::size_t(tiles_x) * tiles_y * tiles_z;
    const std::size_t t = std::size_t(i / kFieldTile) +
                          std::size_t(tiles_x) * (j / kFieldTile + std::size_t(tiles_y) * (k / kFieldTile));
    std::int32_t slot;
    std::memcpy(&slot, &values[t], sizeof slot);
    if (slot < 0) return values[tiles + t];
    return values[2 * tiles + std::size_t(slot) * 512 + std::size_t(i % kFieldTile) +
                  kFieldTile * (std::size_t(j % kFieldTile) + kFieldTile * std::size_t(k % kFieldTile))];
  }
  /// Signed insideness sign * (value - iso) at sample (i, j, k): > 0 inside, <= 0 outside.
  /// Non-finite samples read -1 (outside).
  float signed_at(int i, int j, int k, float iso) const {
    const float v = sample(i, j, k);
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
  /// The sparse layout of `grid` from index `lo` (a leaf corner) over nx x ny x nz samples.
  void fill_tiles(const openvdb::FloatGrid& grid, const openvdb::Coord& lo, const std::string& path);
  /// Sparse: when brick (a, b, c) (samples up to i1, j1, k1) reads only tiles without storage,
  /// its range and slope from their constants, and true; else false (scan its samples).
  bool constant_brick(int a, int b, int c, int i1, int j1, int k1, std::array<float, 2>& range,
                      float& slope) const;

 public:
  /// The index-space box [box[0], box[1]] x [box[2], box[3]] x [box[4], box[5]] (samples) of
  /// every brick that straddles `iso`, specks included: each crossing of the trilinear field lies
  /// in it, and outside it the field keeps one sign along any path (neighbouring bricks share
  /// their face samples). False when no brick straddles (no surface).
  bool straddling_box(float iso, std::array<int, 6>& box) const;
};

}  // namespace isocurv::volume
