#pragma once
// Internals shared by the per-vertex mesh estimators (batagelo, prantl, the fits, meyer): vertex
// normals, 1-ring neighbours, tangent frames, small symmetric solves and the diagonalisation that
// turns a tangent-plane tensor into the CurvatureField arrays. Double precision throughout.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"
#include "curvature/vertex_corners.h"

namespace isocurv::curvature::detail {

using V3 = Eigen::Vector3d;

inline V3 to_v3(const Vec3f& p) { return V3(p[0], p[1], p[2]); }
inline Vec3f to_f3(const V3& v) { return {float(v.x()), float(v.y()), float(v.z())}; }
inline bool repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

/// Which vertex normals a mesh estimator uses.
enum class NormalSource {
  options,  ///< options.vertex_normals where given (and usable), else options.normal_weights
  uniform,  ///< the normalised sum of the unit face normals (Batagelo's protocol), then as above
};

/// Unit vertex normals (zero for a vertex with no usable triangle and no usable given normal):
/// the face normals summed with options.normal_weights (Max or area), or with unit weights for
/// NormalSource::uniform; an entry of options.vertex_normals that is finite and non-zero replaces
/// the mesh normal of its vertex.
std::vector<V3> vertex_normals(const Mesh& mesh, const Options& options,
                               NormalSource source = NormalSource::options);

/// The distinct 1-ring neighbours of every vertex (over triangles without a repeated index), in
/// increasing index order: neighbours of v are ids[offsets[v] .. offsets[v + 1]).
struct Neighbours {
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> ids;
};
Neighbours vertex_neighbours(const Mesh& mesh);
/// The same from an adjacency already built for the mesh (build_vertex_corners): linear time.
Neighbours vertex_neighbours(const Mesh& mesh, const VertexCorners& corners);

/// Per vertex the sum of Meyer et al.'s mixed corner areas (the "Area" array).
std::vector<double> mixed_vertex_areas(const Mesh& mesh);

/// 1 on vertices of an edge that only one triangle (without a repeated index) uses.
std::vector<std::uint8_t> boundary_flags(const Mesh& mesh);

/// Orthonormal tangent basis (u, v), (u, v, n) right-handed, from the unit normal alone (Duff et
/// al. 2017; the same as the Rusinkiewicz reference's).
void tangent_basis(const V3& n, V3& u, V3& v);

/// Rotates the tangent pair (u, v) about u x v -> n, the smallest rotation taking that normal onto
/// n; for opposite normals a half turn about u.
void rotate_to_plane(V3& u, V3& v, const V3& n);

/// Solves the symmetric N x N system A x = b by LDL^T without pivoting. False (x untouched) when a
/// pivot is not above kPivotTolerance times the largest diagonal entry (tolerances.h), the rule
/// the Rusinkiewicz reference and the kernels use.
template <int N>
bool ldlt_solve(const Eigen::Matrix<double, N, N>& A, const Eigen::Matrix<double, N, 1>& b,
                Eigen::Matrix<double, N, 1>& x);

/// The principal curvatures and directions of the symmetric tangent tensor (ku, kuv, kv) in the
/// frame (u, v) with normal n: k1 >= k2, (d1, d2, n) right-handed. One Jacobi rotation, as in the
/// Rusinkiewicz reference.
struct Principal {
  double k1 = 0, k2 = 0;
  V3 d1 = V3::Zero(), d2 = V3::Zero();
};
Principal diagonalise(double ku, double kuv, double kv, const V3& u, const V3& v, const V3& n);

/// Allocates the arrays every mesh estimator fills (normals, area, k1, k2, H, K, ShapeIndex,
/// Curvedness, AO, Boundary, Unreliable) and, when with_directions, dir1 and dir2; dcurv stays
/// empty. Area and Boundary are filled here.
CurvatureField allocate_field(const Mesh& mesh, bool with_directions);

/// Writes vertex i's normal and curvatures, and the quantities derived from k1 and k2.
void set_vertex(CurvatureField& out, std::size_t i, const V3& normal, double k1, double k2,
                float ao_scale);

/// One vertex as a per-vertex fit sees it: position, unit normal, tangent frame (u, v, n) and its
/// distinct 1-ring neighbours' positions and normals.
struct VertexRing {
  V3 p, n, u, v;
  std::vector<V3> q, nq;
  /// The one rule's bound on a curvature (implausible_above, field_stats.h: 2 / mean edge of the
  /// whole surface); 0: none.
  double plausible = 0;
};

/// The fits that sample normal curvatures (quadric, sampling) on what marching cubes leaves: a
/// fit is refused (the vertex flagged) when its largest principal curvature exceeds this many
/// times its largest |sample|. Three sample directions 60 degrees apart bound max(|k1|, |k2|) by
/// twice the largest |sample| (Euler: k(t) = H + D cos 2t, D >= 0, and one of three angles 2t
/// 120 degrees apart has cos 2t >= 1/2); beyond it the directions nearly lie on two lines and the
/// fit extrapolates noise (MC's valence-4 vertices, two pairs of opposite neighbours).
inline constexpr double kSampleExtrapolation = 2;
/// ...except below this fraction of the plausible bound (a plane's rounding, 1/1000 of it).
inline constexpr double kSampleFlatFloor = 1e-3;

/// For those fits: true when `kappa` (a sample's normal curvature) is finite and within
/// r.plausible (a chord turning more than the mesh can show: marching cubes' tiny edges, whose
/// 2 (P - q).n / |P - q|^2 divides noise by a tiny length), and then `largest` takes |kappa| in.
/// A sample it refuses is left out of the fit.
inline bool keep_sample(double kappa, const VertexRing& r, double& largest) {
  if (!std::isfinite(kappa) || (r.plausible > 0 && std::abs(kappa) > r.plausible)) return false;
  largest = std::max(largest, std::abs(kappa));
  return true;
}

/// For those fits: true when the fitted tensor (e, f, g) is determined by its samples (largest
/// |sample| `largest`): max(|k1|, |k2|) = |H| + sqrt(((e - g) / 2)^2 + f^2) within
/// kSampleExtrapolation x largest, or within kSampleFlatFloor x r.plausible.
inline bool determined_by_samples(const V3& t, double largest, const VertexRing& r) {
  const double k = std::abs(t[0] + t[2]) / 2 + std::hypot((t[0] - t[2]) / 2, t[1]);
  return k <= kSampleExtrapolation * largest || k <= kSampleFlatFloor * r.plausible;
}

/// A fit of one vertex: its second fundamental form (e, f, g) in (u, v) (outward normals: a
/// sphere gives e = g = 1/R), or false when it cannot be solved (then the vertex is flagged).
using VertexFit = std::function<bool(const VertexRing&, V3& tensor)>;

/// Runs `fit` on every vertex with a non-zero normal and at least min_neighbours neighbours and
/// fills k1, k2, dir1, dir2, H, K, the derived arrays, Area and Boundary; dcurv stays empty. A
/// vertex the fit cannot use gets zero curvature, dir1 = u, dir2 = v and Unreliable = 1. Each
/// ring's `plausible` is implausible_above(mesh, options.piece) (collective with a piece).
CurvatureField fit_each_vertex(const Mesh& mesh, const Options& options,
                               std::size_t min_neighbours, const VertexFit& fit);

/// Least squares A x = b by column-pivoting QR; false when A (scaled by its columns' norms) has
/// rank below its column count (relative threshold 1e-8) or the solution is not finite.
bool least_squares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, Eigen::VectorXd& x);

}  // namespace isocurv::curvature::detail

#include "curvature/detail/local_geometry_impl.h"
