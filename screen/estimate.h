#pragma once
// Per-pixel curvature on a G-buffer (SEEDS-SPEC 4.4 P-SS, P-LOD, P-DISC; 4.5 P-MEL): Prantl et
// al.'s per-triangle shape operator on pixel triangles, with the level of detail and the
// depth-discontinuity rule, and Mellado et al.'s screen-space sphere fit (the paper's baseline).
// The OpenCL kernels (screen_kernels.cl) and their double-precision C++ reference.
// Tested in tests/screen/scenes.h.
#include <cstdint>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "screen/gbuffer.h"

namespace isocurv::screen {

enum class ScreenEstimator { prantl, mellado };
/// How a pixel's eye depth z becomes the depth d in [0, 1] that the LOD and the discontinuity
/// rule read: `window` is the paper's window depth ((1/n - 1/z) / (1/n - 1/f), perspective;
/// (z - n) / (f - n), orthographic), `linear` is z / f (f: the far plane).
enum class DepthMapping { window, linear };
/// What a neighbour across a discontinuity does: `report` (Prantl's report, eq. 7.13): it falls
/// back to the 1-pixel neighbour in its direction; `paper` (the paper's 3.4): its triangles are
/// rejected. Either way, when no fan triangle is left the single 1-pixel triangle is used.
enum class DiscontinuityRule { report, paper };

struct ScreenOptions {
  ScreenEstimator estimator = ScreenEstimator::prantl;
  int edges = 2;     ///< 2 (eq. 17, the fastest) or 3 (eq. 9-11) edges per pixel triangle
  bool lod = false;  ///< level of detail: step s = floor(size_max f^(-2d)) + 1 (report eq. 7.12)
  int size_max = 8;  ///< the LOD's largest extra step (pixels)
  int fan = 4;       ///< triangles around the pixel when s > 1: 4 (report) or 8 (paper)
  DepthMapping depth = DepthMapping::linear;
  DiscontinuityRule rule = DiscontinuityRule::report;
  /// Reject pixel triangles whose corner normals differ by more than this (degrees); <= 0: off.
  double max_normal_angle_deg = 0;
  int mellado_radius = 4;  ///< Mellado: the pixels within this radius (pixels) are fitted
};

/// Per-pixel results, the G-buffer's layout (x + width y, y up).
struct ScreenCurvature {
  int width = 0, height = 0;
  std::vector<float> H;             ///< mean curvature (outward normals: a sphere has +1/R)
  std::vector<float> K;             ///< Gaussian curvature (0 for Mellado, which gives none)
  std::vector<std::uint8_t> valid;  ///< 1 where estimated; silhouettes and discontinuities: 0
  std::vector<std::uint8_t> step;   ///< the step s the pixel used (1 without LOD)
  std::size_t valid_count() const;
};

/// How titles and --json name the estimator of `options`: "screen-space Prantl, 2 edges[, LOD]"
/// or "screen-space Mellado, radius 4 px", followed by ", smoothed S voxels" when the volume was
/// smoothed first (`smoothing_voxels` > 0, volume::DenseField::smooth).
std::string estimator_label(const ScreenOptions& options, double smoothing_voxels = 0);

/// The LOD far distance f = max(far plane, 100) and the discontinuity threshold tau = 1 / f.
double lod_far(const GBuffer& g);

/// The rule, per pixel c of a valid G-buffer pixel, d its depth (ScreenOptions::depth):
/// Prantl: s = 1 without LOD, else floor(size_max f^(-2d)) + 1. With s > 1, the neighbours
/// s pixels right, up, left, down (and the diagonals for the 8-fan) that are valid and within
/// tau = 1/f in depth give the fan triangles (c, n_k, n_k+1), each solved by
/// curvature::prantl_triangle with `edges` edges; H and K are the means over the solved ones.
/// With s = 1, or when none solved: the first solvable of (c, R, U), (c, U, L), (c, L, D),
/// (c, D, R) with 1-pixel neighbours. None: the pixel is invalid.
/// Mellado: the valid pixels within mellado_radius (and tau in depth), at least 6, fit an
/// algebraic sphere with normals (weights (1 - r^2/h^2)^4, h = 1.5 x the farthest one);
/// H = 2 u_q / |u_l|. Double precision, TBB over rows, deterministic.
/// @throw Error for options out of range or a G-buffer whose arrays do not match its size
ScreenCurvature estimate_reference(const GBuffer& g, const ScreenOptions& options = {});

/// The same on `device` in float. @param work_group work-group size of the launch
/// @throw Error as estimate_reference, or for an OpenCL failure
ScreenCurvature estimate(const GBuffer& g, Device& device, const ScreenOptions& options = {},
                         int work_group = 64);

}  // namespace isocurv::screen
