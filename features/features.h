#pragma once
// features::compute: neighbourhood features of a surface at a radius of support
// (Andreadis et al. 2015, seed 004, section 5.1; SEEDS-SPEC.md section 6.3):
// quantities that integrate over a ball around each vertex instead of
// differentiating at it, so they measure shape at a chosen scale and are far
// less sensitive to voxel-scale noise than per-vertex curvature.
// Tested in tests/features/feature_helpers.h, tests/features/test_features.cpp.
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "volume/volume.h"

namespace isocurv::features {

/// The features, by the array name they are written under.
///  LBE    local bending energy (eq. 5): sum A_i |n - n_i|^2 / |p - q_i|^2 /
///  sum A_i over the
///         vertices q_i within Euclidean distance r (reached along mesh edges),
///         A_i their Area. 1/length^2; exactly 1/R^2 on a sphere, 0 on a plane,
///         Curvedness^2 as r -> 0.
///  NSV    normalised sphere volume by horizon sampling, the paper's form (eq.
///  6 with its minus
///         signs restored): mean over the same samples of (1 - (q_i - p).n /
///         |q_i - p|) / 2, area-weighted. In [0, 1]; 1/2 on a plane. Kept
///         faithful for comparison: the mean curvature it implies is 8/9 of the
///         true one on a sphere (the paper's bias).
///  Vr     the volume integral invariant: volume of the solid inside the ball
///  B(p, r), length^3,
///         from the volume's trilinear field (volume input only).
///  H_ii   mean curvature from the volume integral invariant (Hulin-Troyanov,
///  eq. 7: Vr =
///         2 pi r^3 / 3 - pi H r^4 / 4 + O(r^5)), resolved by radius: the
///         quadrature's per-radius terms are fitted as d + H t^2 / 2, which
///         removes the vertex's offset d from the surface (eq. 7 at one radius,
///         8/(3r) - 4 Vr / (pi r^4), turns it into an error of 4 d / r^2: noise
///         on CT data); exact on spheres. On mesh input (no volume), the same
///         integral from the surface samples, the "mean height" form -(4/r^2)
///         sum A_i (q_i - p).n / sum A_i.
///  K_ii   Gaussian curvature from the geodesic disc's area GA_r
///  (Bertrand-Diquet-Puiseux,
///         eq. 10: 12 (pi r^2 - GA_r) / (pi r^4) + O(r^2)), solved from the
///         constant-curvature disc area 2 pi (1 - cos(r sqrt K)) / K instead,
///         which is exact on spheres. GA_r is the area of the mesh where the
///         geodesic distance (fast marching over the triangles, piecewise
///         linear) is at most r.
///  SI_ii  shape index from H_ii and K_ii (eq. 8-9): k = H_ii +- sqrt(max(0,
///  H_ii^2 - K_ii)),
///         (2/pi) atan2(k1 + k2, k1 - k2): +1 on a cap, the project's
///         convention.
/// Sign convention as everywhere: normals point out of the object, convex is
/// positive.
enum class Feature { LBE, NSV, Vr, H_ii, K_ii, SI_ii };

/// "LBE", "NSV", "Vr", "H_ii", "K_ii", "SI_ii".
const char *feature_name(Feature f);
/// Parses a comma-separated list of names (case-sensitive, as written above);
/// "all" gives every feature. @throw Error naming an unknown entry.
std::vector<Feature> parse_features(const std::string &list);

/// What to compute.
struct Options {
  /// Radii of support, world units, each > 0. Several radii give one set of
  /// arrays per radius.
  std::vector<double> radii;
  /// Their names as the user wrote them ("4", "0.5", "4%"), used for the array
  /// suffixes "_r<name>" when there are several radii; empty: the radii printed
  /// with %g.
  std::vector<std::string> radius_names;
  /// Which features; empty (the default): every one the input allows (Vr needs
  /// a volume).
  std::vector<Feature> features;
  /// Volume quadrature of Vr (SEEDS-SPEC.md A-VR (i)): azimuths around the
  /// normal and Gauss-Legendre radii. Exact on spheres for any counts; more
  /// resolve rougher surfaces.
  int azimuths = 16;
  int radial = 6;
  /// The isovalue the mesh was extracted at (volume features read the field's
  /// inside side).
  double isovalue = 0;
  /// How LBE, NSV and K_ii see the neighbourhood (SEEDS-SPEC.md A-MC, A-ADA).
  ///  0: exactly: the mesh's vertices within r, reached along its edges and
  ///     weighted by their Area, and the geodesic disc by fast marching over
  ///     the triangles. The reference; cost grows with r^2.
  ///  N > 0 (volume input only): N samples per vertex on the volume's trilinear
  ///     isosurface: N / 16 curves (rounded down to an even count, at least 2)
  ///     of 16 steps per radius, the normal-plane cuts of a web rotated per
  ///     vertex (features/detail/geodesic_web.h). Cost independent of r.
  int samples = 0;
  /// Sampled path: trace the second half of the curves only where the first
  /// half's per-azimuth mean curvatures vary by more than adaptive_threshold
  /// (variance over mean square): two-stage adaptive sampling.
  bool adaptive = false;
  double adaptive_threshold = 0.01;
  /// Sampled path: the seed of the per-vertex rotations (deterministic).
  std::uint32_t seed = 0;
  /// Compute only at these vertices (each < the vertex count); the others get
  /// zeros. Empty (the default): every vertex. For probes and benchmarks of the
  /// exact path, whose cost grows with r^2. The device path computes all.
  std::vector<std::uint32_t> vertices;
};

/// Appends the radii of `list` ("4,0.5,2%": world units, a trailing % of `diagonal`) to
/// o.radii, each with its name as written (o.radius_names, the array suffixes). @throw Error
/// "'ITEM' is not a positive number (...)" for a bad item.
void parse_radii(const std::string &list, double diagonal, Options &o);

/// One named per-vertex array.
struct Array {
  std::string name;          ///< e.g. "H_ii", or "H_ii_r4" with several radii
  std::vector<float> values; ///< one value per vertex
};

/// The output: arrays in the order of options.radii, then options.features; and
/// per vertex whether some neighbourhood left what is known (the volume's
/// domain, or an open boundary of the mesh within r): its values are finite but
/// biased.
struct FeatureField {
  std::vector<Array> arrays;
  std::vector<std::uint8_t>
      boundary; ///< 1 where a ball of some radius was incomplete
  /// Sampled path: the samples taken, over all vertices and radii (curves
  /// traced x 16), and the curves' share that adaptive sampling traced.
  std::uint64_t samples_taken = 0;
  double traced_fraction = 1;
};

/// Computes the features at every vertex of `mesh`.
/// @param mesh    the surface (world units), consistently oriented outwards
/// @param field   its curvature: `normals` (unit, outward) and `area`
/// (per-vertex Area) are used
/// @param volume  the volume it came from, or nullptr for a mesh file (then Vr
/// is unavailable and
///                H_ii uses the surface form; asking for Vr is an error)
/// @param options radii, features, quadrature
/// @throw Error for a radius that is not positive and finite, a field without
/// normals or areas
///        of the mesh's size, Vr or samples > 0 without a volume, or samples
///        under 32.
/// Threading: parallel over vertices (TBB); deterministic (the sampled path's
/// rotations are hashes of the vertex and the seed; sums in a fixed order).
/// Cost: vertices x (neighbours within r, or samples x ~5 field reads, plus
/// azimuths x radial x ~16 field samples for Vr/H_ii on a volume).
FeatureField compute(const Mesh &mesh, const curvature::CurvatureField &field,
                     const volume::Volume *volume, const Options &options);

/// The same on an OpenCL device: the sampled path's web and the volume
/// quadrature of Vr and H_ii run as kernels (features_kernels.cl), one work
/// item per vertex; compute() is their double-precision reference. The exact
/// path (samples = 0) runs on the host as in compute().
/// @throw Error as compute(), and for a device failure.
/// Threading: one call per device at a time.
FeatureField compute(const Mesh& mesh, const curvature::CurvatureField& field,
                     const volume::Volume* volume, const Options& options, Device& device);

} // namespace isocurv::features
