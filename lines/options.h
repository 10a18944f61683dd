#pragma once
// Options of the lines stage (lines::extract and lines::extract_reference) and
// the thresholds they resolve to on a given curvature field.
// Tested in tests/lines/test_thresholds.cpp.
#include "curvature/curvature_field.h"
#include "lines/line_types.h"

namespace isocurv::lines {

/// What to extract and the (scale-free) thresholds. The thresholds are relative
/// to the mesh's typical curvature m, the median over vertices of max(|k1|,
/// |k2|), so that the same defaults suit a unit sphere and a 512^3 CT scan.
struct Options {
  LineSelection lines{true, true, false,
                      false}; ///< default: contours and suggestive contours
  /// Suggestive contours: kept where D_w k_r sin(theta)/cos(theta) (num/den of
  /// the spec) exceeds t_d = suggestive_threshold * m^2 (DeCarlo's threshold on
  /// the derivative); faded in over [t_d, 2 t_d]. 0 keeps every zero crossing
  /// with a positive derivative.
  double suggestive_threshold = 0.05;
  /// Suggestive contours: only where the view is at least this far (degrees)
  /// from the normal, i.e. n.v < cos(angle) (DeCarlo's theta_c).
  double suggestive_angle_deg = 10;
  /// Ridges and valleys: kept where |k| (k1 on ridges, k2 on valleys) at the
  /// line exceeds t_r = ridge_threshold * m; faded in over [t_r, 2 t_r].
  double ridge_threshold = 1.5;
  /// Suggestive contours: passes of 1-ring averaging (each vertex with its
  /// neighbours, every corner's two other vertices counted) over kr and num
  /// before the faces are cut. Marching-cubes meshes carry curvature ripples a
  /// few voxels long whose kr zero crossings have large derivatives (no
  /// threshold on the derivative removes them); a few passes flatten them and
  /// barely move the zero sets of features many edges wide. n.v (the contours)
  /// is never smoothed.
  int smoothing_steps = 4;
};

/// The absolute thresholds of `options` on `field` (units: t_d 1/length^2, t_r
/// 1/length).
struct Thresholds {
  double suggestive = 0;        ///< t_d
  double cos_angle = 1;         ///< cos(theta_c)
  double ridge = 0;             ///< t_r
  double typical_curvature = 0; ///< m (0 for an empty field)
};

/// Resolves `options` on `field` (finite values only; the median is exact).
/// @throw Error for a negative or non-finite threshold, an angle outside [0,
/// 90) or smoothing steps outside 0..100.
Thresholds resolve_thresholds(const curvature::CurvatureField &field,
                              const Options &options);

} // namespace isocurv::lines
