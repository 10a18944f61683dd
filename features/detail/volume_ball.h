#pragma once
// The volume integral invariant Vr(p) = volume of the solid inside the ball
// B(p, r), from the volume's trilinear field (SEEDS-SPEC.md A-VR (i), the
// horizon-per-radius quadrature).
//
// In spherical coordinates about p with the pole along the normal n, a point at
// distance t, azimuth phi and elevation beta (sine s = sin beta) has volume
// element t^2 dt dphi ds, so
//   Vr = integral over phi in [0, 2 pi), t in [0, r] of t^2 L(t, phi) dt dphi,
// with L the length of { s in [-1, 1] : the point is inside } on the arc of
// radius t in the normal half-plane at azimuth phi. For a surface crossing each
// arc once at s*, L = 1 + s* and Vr - 2 pi r^3 / 3 = integral t^2 s* dt dphi;
// on a sphere s* = -t / (2R) exactly, so the quadrature (uniform azimuths,
// Gauss-Legendre radii) is exact there. Each arc is sampled at kArcSamples
// values of s and every sign change refined by regula falsi on the field, so
// several crossings (thin plates, other sheets inside the ball) are counted.
#include <openvdb/openvdb.h>

#include <vector>

#include "volume/volume.h"

namespace isocurv::features::detail {

/// Samples of s per arc before refinement, and refinement steps per crossing.
inline constexpr int kArcSamples = 9;
inline constexpr int kRefineSteps = 5;

class VolumeBall {
public:
  /// @param azimuths, radial  quadrature counts (azimuths >= 1, radial
  /// in 2..16)
  VolumeBall(const volume::Volume &volume, double isovalue, int azimuths,
             int radial);

  struct Result {
    double vr = 0; ///< volume of the solid inside B(p, r)
    double h_fit =
        0; ///< mean curvature from the radius-resolved integral (below)
    bool leaves = false; ///< the ball leaves the volume's data domain
  };

  /// Vr at world point p with unit outward normal n, and the mean curvature
  /// fitted over the quadrature's radii: per radius t the azimuth mean m(t) = t
  /// * mean(1 - L(t, phi)), which is d + H t^2 / 2 + O(t^3) for a vertex at
  /// signed distance d outside the surface (on a sphere, d + t^2 / (2R)
  /// exactly); a least-squares line in t^2 gives H without the vertex's offset,
  /// which eq. 7 at one radius turns into an error of 4 d / r^2 (noise and the
  /// trilinear surface's wobble on CT data). Not thread-safe: one VolumeBall
  /// per thread (each holds a grid accessor).
  Result inside_volume(const openvdb::Vec3d &p, const openvdb::Vec3d &n,
                       double r);

  /// The Gauss-Legendre nodes and weights on [-1, 1] of the radial quadrature.
  const std::vector<double>& nodes() const { return nodes_; }
  const std::vector<double>& weights() const { return weights_; }

 private:
  double inside(const openvdb::Vec3d &world); ///< > 0 inside, <= 0 outside
  double inside_at_index(
      const openvdb::Vec3d &index); ///< the same at an index-space point
  const volume::Volume &volume_;
  openvdb::FloatGrid::ConstAccessor accessor_;
  double isovalue_, sign_;
  int azimuths_, radial_;
  std::vector<double> nodes_, weights_; ///< Gauss-Legendre on [-1, 1]
  std::vector<double> outside_;         ///< scratch, per radius
};

} // namespace isocurv::features::detail
