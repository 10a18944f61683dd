#pragma once
// The volume estimator's default scale, per vertex, from the data and the shape: at each vertex the
// world scale sigma that minimises the expected squared error of H, the noise's variance plus the
// smoothing's bias squared, both measured from two pilot evaluations (curvature/volume_estimate.h
// runs them and then evaluates each vertex at its scale).
//
// The noise: white voxel noise of deviation n (value units) on cells of volume v (sx sy sz, world
// units^3), smoothed by a Gaussian of world deviation sigma, gives the sum of the two tangential
// second derivatives a deviation n sqrt(v) / (2 pi^3/4 sigma^3.5); H is that over 2 |g|, so
//   N(sigma) = kNoiseH n sqrt(v) / (|g(sigma)| sigma^3.5),
// with |g(sigma)| the gradient at the vertex, which falls as the smoothing adds to the edge's own
// blur b: |g(sigma)| = |g(s1)| sqrt((b^2 + s1^2) / (b^2 + sigma^2)), b from the median gradients at
// the two pilot scales. (On bench_accuracy's CT-like sphere this predicts the measured error to
// within 5% at 1x and 2x resolution.) A binary volume's noise is its staircase: modelled as white
// noise of kBinaryNoise times the contrast, which makes its scale grow in voxels as the grid
// refines (the staircase error falls as the voxel count under the smoothing grows).
//
// The bias: the level set through a vertex of the smoothed field moves with the surface's mean
// curvature (like mean-curvature flow, by sigma^2 H / 2 per unit time), so its H is off by about
// sigma^2 L / 2, L the surface Laplacian of H: zero on spheres and cylinders, large on thin tori
// and saddles. L^2 is measured, per region, from the difference D = H(s2) - H(s1) of the two
// pilots: E[D^2] = ((s2^2 - s1^2) / 2)^2 L^2 + var(D), averaged over the vertices within
// kRegionScales * s2 (a grid of cells that size, the 27 around the vertex), var(D) from the noise
// model (the two pilots' noise correlated by (2 s1 s2 / (s1^2 + s2^2))^3.5).
//
// Each vertex then takes the scale of the ladder s1 sqrt(2)^j within [lo, hi] whose
// N(sigma)^2 + (sigma^2 L / 2)^2 is least.
// Tested in tests/curvature/adaptive_scale_test.cpp.
#include <cstddef>
#include <vector>

#include "core/mesh.h"
#include "core/surface_piece.h"

namespace isocurv::curvature {

/// 1 / (4 pi^(3/4)): H's noise deviation factor (see above).
inline constexpr double kNoiseH = 0.10608;
/// A binary volume's staircase as white noise: this fraction of the contrast (chosen on
/// bench_accuracy --refine's binary torus, sphere and part at 1x, 2x and 4x).
inline constexpr double kBinaryNoise = 0.15;
/// The region over which L^2 is averaged, in pilot scales s2 (the cell size of its grid).
inline constexpr double kRegionScales = 1.0;
/// The wider region's cell side, in kRegionScales s2, and at most kWideRegionLimit times the
/// choice's largest scale (which keeps it within the ghost margin of a distributed piece).
inline constexpr double kWideRegion = 3.0;
inline constexpr double kWideRegionLimit = 1.5;
/// The shape's limit: no vertex is measured at a scale above kShapeScale / kappa, kappa its
/// largest principal curvature (ScalePilots::kappa). Past it the bias is no longer the quadratic
/// sigma^2 L / 2 the pilots measure (a torus of tube radius r: its level sets deform at
/// sigma ~ r / 2), and the smoothed isosurface that binary volumes are measured on shrinks by
/// more than the correction holds (volume_estimate.h, kSurfaceY1: fitted to sigma / r = 1/2).
inline constexpr double kShapeScale = 0.35;
/// The same for binary volumes, whose staircase costs more than the bias up to about half the
/// curvature radius (bench_accuracy --refine: binary torus best at sigma kappa 0.5 to 0.7).
inline constexpr double kBinaryShapeScale = 0.5;
/// NoiseModel::staircase: the quantile of the vertices' largest principal curvature the scale
/// is taken from (the binary torus's inner equator, a part's rounded edges).
inline constexpr double kBinaryCurvatureQuantile = 0.99;
/// The region's excess must exceed this many of its standard errors to count as bias: a sphere's
/// L is zero, and without it the noise in the estimate would cap its scale.
inline constexpr double kSignificance = 2.0;
/// Surface area per marching-cubes vertex, in voxel faces (a sphere of radius 16 voxels: 4762
/// vertices over 3217 voxel faces).
inline constexpr double kVertexArea = 0.68;
/// Rungs of the scale ladder per octave.
inline constexpr int kLadderSteps = 4;
/// The largest scale of the choice, in voxels (the geometric mean spacing).
inline constexpr double kAdaptiveMaxVoxels = 12.0;

/// What white voxel noise does to H (see above).
struct NoiseModel {
  double noise = 0;        ///< voxel noise deviation, value units
  double cell_volume = 1;  ///< sx sy sz, world units^3
  double shape_scale = kShapeScale;  ///< kShapeScale, or kBinaryShapeScale for binary volumes
  /// A binary volume: its staircase is no white noise, and per-vertex scales stitched the
  /// curvatures of differently smoothed surfaces together (Gauss-Bonnet gaps of 1.5-4% on binary
  /// tori and boxes), so the whole surface takes one scale from its shape: shape_scale over the
  /// kBinaryCurvatureQuantile of kappa, never under the first pilot (kBinaryScaleVoxels: under it
  /// the staircase dominates; the binary torus at h = 0.5, 0.039 at 1.4 voxels, 0.016 at 2).
  /// In world units for a given shape, so in voxels it grows as the grid refines.
  bool staircase = false;
};

/// N(sigma): H's noise deviation at world scale `sigma` where the gradient is `gradient`.
double h_noise(const NoiseModel& model, double gradient, double sigma);

/// Two pilot evaluations of every vertex: H and |g| at world scales s1 < s2.
struct ScalePilots {
  double s1 = 0, s2 = 0;
  const std::vector<float>* H1 = nullptr;
  const std::vector<float>* g1 = nullptr;
  const std::vector<float>* H2 = nullptr;
  const std::vector<float>* g2 = nullptr;
  /// max(|k1|, |k2|) per vertex (the driver takes the smaller of the two pilots' on grey
  /// volumes, the first's on binary ones): the shape's own length (see kShapeScale).
  const std::vector<float>* kappa = nullptr;
  /// Optional: the largest scale each vertex may take (world units), for reasons outside the
  /// noise and the shape (the box of a volume whose border is not flat).
  const std::vector<float>* limit = nullptr;
  /// The second pilot evaluated a sample of the vertices, one in about `stride` (H2 NaN and g2
  /// 0 elsewhere): each of its values stands for that many vertices' area.
  double stride = 1;
};

/// What the choice measured (for the report).
struct ScaleChoiceReport {
  double blur = 0;  ///< the edge's own blur b, world units
};

/// Each vertex's scale (world units, on the ladder s1 2^(j / kLadderSteps) within [lo, hi]; lo <= s1 <=
/// s2 <= hi) for `positions` from the pilots (see above). A vertex without a gradient at s1 keeps
/// s1. Deterministic whatever the vertices' order: with a `piece` (core/surface_piece.h,
/// collective) its own vertices get the single process's scales when its margin holds every
/// vertex within 2 kRegionScales s2 of them. Throws isocurv::Error on inconsistent sizes or
/// scales.
std::vector<float> choose_vertex_scales(const Positions& positions, const NoiseModel& model,
                                        const ScalePilots& pilots, double lo, double hi,
                                        const SurfacePiece* piece = nullptr,
                                        ScaleChoiceReport* report = nullptr);

}  // namespace isocurv::curvature
