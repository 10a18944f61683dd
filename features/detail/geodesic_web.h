#pragma once
// The sampled neighbourhood of one vertex (features' sampled path, SEEDS-SPEC.md A-MC and A-ADA
// adapted to a volume): a web of M curves on the volume's trilinear isosurface, each the surface's
// cut by a normal plane at one azimuth, traced from the vertex in steps of r / kWebSteps of arc
// length. The double-precision reference of features_kernels.cl's `features_web`, which runs
// the same steps in float.
//
// Why curves and not the paper's tangent-disc points projected along the normal: a curve stays
// on the vertex's own sheet (as the exact path's walk over mesh edges does; projections jump to
// other sheets and fail where the surface is not a graph over the tangent plane), and its arc
// length is the geodesic distance along the cut, which is the geodesic distance to third order;
// the odd fourth-order term cancels between opposite azimuths, so the disc {s <= r} has the
// geodesic disc's area to O(r^6) and K_ii keeps Bertrand-Diquet-Puiseux's O(r^2) accuracy.
//
// Quadrature: at a point of a curve at distance rho from the normal axis, with e the curve's
// in-plane normal and n_c the surface normal there, the surface element is
// dA = rho / |e . n_c| ds dphi (exact, from the cut's geometry). The M azimuths are evenly spaced
// and rotated per vertex by a hash of its index and the seed (the "randomly rotated stratified
// pattern": evenly spaced azimuths integrate the curvature's harmonics exactly, where jittered
// ones would add noise of the size of K_ii's signal); arc length by the trapezoid rule on the
// traced nodes. Adaptive (A-ADA): the even azimuths first; the odd ones only where the
// per-azimuth mean curvatures vary by more than the surface's second-order shape explains
// (adaptive_needs_more).
#include <array>
#include <cstdint>

#include "volume/dense_field.h"

namespace isocurv::features::detail {

/// Steps of r / kWebSteps per geodesic radius; a step whose corrector fails is retried at half
/// the length, down to 1 / kWebStepDivisions of it, and the length doubles back after each
/// success. A curve stops after kWebMaxAttempts steps and retries, or kWebMaxLength r of arc
/// (it may need more than r to leave the Euclidean ball). Samples per vertex = azimuths x
/// kWebSteps.
inline constexpr int kWebSteps = 16;
inline constexpr int kWebStepDivisions = 8;
inline constexpr int kWebMaxAttempts = 6 * kWebSteps;
inline constexpr double kWebMaxLength = 3;
/// Newton steps that move the vertex onto the trilinear surface along its normal (each at most
/// half a voxel), and corrector steps that bring each predicted node back onto the surface.
inline constexpr int kProjectSteps = 4;
inline constexpr int kCorrectorSteps = 4;
/// A node whose |field| / |gradient| before the last corrector step exceeds this (in voxels) is
/// off the surface (the cut turned or ended within a step): its curve stops there and the vertex
/// is flagged.
inline constexpr double kOffSurface = 0.5;
/// Smallest |e . n_c| in the area element (a cut grazing the surface).
inline constexpr double kMinCos = 0.05;

/// What the web of one vertex gives.
struct WebSums {
  double lbe = 0;         ///< local bending energy (eq. 5), 1/length^2
  double nsv = 0.5;       ///< normalised sphere volume, the paper's horizon form (eq. 6)
  double disc_area = 0;   ///< area of the geodesic disc of radius r
  int azimuths = 0;       ///< azimuths traced (M, or M / 2 where adaptive stopped early)
  bool boundary = false;  ///< a curve left the data domain or lost the surface before leaving r
};

/// The adaptive test on the first half's per-azimuth mean curvatures g(phi) (their sum, sum of
/// squares, sums of g cos 2 phi and g sin 2 phi, count): whether their variance, less the part a
/// quadric explains (a + b cos 2 phi + c sin 2 phi: the normal curvature's form, which the first
/// half's evenly spaced azimuths already integrate exactly), exceeds threshold x their mean
/// square. The plain variance below 5 azimuths.
bool adaptive_needs_more(double sum, double sum_sq, double sum_cos2, double sum_sin2, int count,
                         double threshold);

/// A hash of the vertex index and the seed, as a rotation in [0, 2 pi) (the kernel's too).
double web_rotation(std::uint32_t vertex, std::uint32_t seed);

/// The web sums of vertex `vertex` at world point p with unit outward normal n (a hint: the
/// vertex first moves onto the trilinear surface, and the field's normal there is used).
/// @param azimuths  M >= 2, even
/// @param adaptive  trace the odd azimuths only where the even ones disagree (threshold: the
///                  variance of the per-azimuth mean curvatures over their mean square)
WebSums trace_web(const volume::DenseField& field, float iso, const std::array<double, 3>& p,
                  const std::array<double, 3>& n, double r, int azimuths, bool adaptive,
                  double threshold, std::uint32_t vertex, std::uint32_t seed);

}  // namespace isocurv::features::detail
