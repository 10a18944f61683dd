#pragma once
// Options of the curvature estimator (curvature::estimate and curvature::estimate_reference).
// Tested in tests/curvature/estimator_protocols_test.cpp (through its users).
#include <vector>

#include "ao/method.h"
#include "core/mesh.h"
#include "core/surface_piece.h"

namespace isocurv::curvature {

/// How face normals are weighted into a vertex normal when the normals come from the mesh.
enum class NormalWeights {
  /// Max (1999): face normal times sin(angle) / (|e1| |e2|) of the corner's two edges. Exact for
  /// vertices on a sphere; what Rusinkiewicz and trimesh2 use. The default.
  max,
  /// Face area: robust when tiny, badly shaped triangles (marching cubes near grid points) would
  /// otherwise dominate the Max weights.
  area,
};

/// How Batagelo & Wu's one-pass tensor weighs each 1-ring neighbour's row (their section 4.1).
enum class NeighbourWeights {
  uniform,         ///< w = 1: every neighbour alike (the paper's default)
  inverse_square,  ///< w = 1 / |x|^2, x the neighbour's offset in the tangent plane: near ones count more
};

/// The curvature estimators behind curvature::estimate_field (curvature/estimator.h).
enum class Estimator {
  /// Rusinkiewicz's estimator on the mesh (Griffin et al.'s parallel form): curvature from the
  /// variation of the vertex normals over each triangle. Needs only the mesh.
  rusinkiewicz,
  /// Curvature of the volume itself, reconstructed at a scale: gradient, Hessian and third
  /// derivatives of the samples prefiltered by a Gaussian and read through a quartic B-spline
  /// (curvature/volume_estimate.h). Needs the volume.
  volume,
  /// The seeds' other mesh estimators and the classic ones they compare against
  /// (curvature/mesh_estimators.h): Batagelo & Wu's one-pass tensor, Prantl et al.'s per-triangle
  /// shape operator from 3 or 2 edges, quadric and cubic fits, normal-curvature sampling, Meyer
  /// et al.'s discrete operators. Each fills only the arrays it can (arrays_filled).
  batagelo,
  prantl3,
  prantl2,
  quadric,
  cubic,
  sampling,
  meyer,
};

/// Where the volume estimator takes each vertex's curvature (curvature/volume_estimate.h).
enum class VolumePoint {
  /// surface on binary volumes (curvature::is_binary), vertex otherwise (resolved_point).
  automatic,
  /// The level set through the vertex: for grey-level volumes, whose marching-cubes vertices lie
  /// within the noise of the surface.
  vertex,
  /// The smoothed isosurface where the vertex's gradient line meets it (kNewtonSteps Newton
  /// steps, at most kMaxShiftVoxels), its curvatures those of the parallel surface about
  /// sigma^2 H further out (k / (1 + e k), e as kSurfaceY1 and kSurfaceY2 say), undoing the
  /// smoothing's shrinkage: for binary volumes, whose vertices sit on the voxel staircase, up to
  /// half a voxel off the surface (evaluated there, a torus of tube radius 4 voxels would be off
  /// by 12%). The field's surface_points are those surface points, for measure::object_measures.
  surface,
};

struct Options {
  /// Which estimator estimate_field runs (estimate() and estimate_reference() are Rusinkiewicz's).
  Estimator estimator = Estimator::rusinkiewicz;
  /// Volume estimator: the Gaussian's standard deviation sigma, world units; 0 (the default)
  /// chooses it from the data (curvature/auto_scale.h). Ignored by the mesh estimators.
  double scale = 0;
  /// Volume estimator: a vertex the scale does not fit (its smoothed surface eroded or merged with
  /// another) is measured at finer scales, down to a floor, as curvature/volume_estimate.h
  /// states. false: such vertices are Unreliable (--scale S1,S2,...).
  bool finer_scales = true;
  /// Volume estimator: where each vertex's curvature is taken (VolumePoint above).
  VolumePoint volume_point = VolumePoint::automatic;
  /// Per-vertex outward normals supplied from outside (e.g. the volume gradient), one per mesh
  /// vertex; they need not be unit length (they are normalised). A zero or non-finite entry falls
  /// back to the mesh normal of that vertex. nullptr (the default): normals from the mesh faces.
  /// The pointee must outlive the call. Mesh estimators only (the volume estimator takes its normals
  /// from the reconstructed gradient).
  const std::vector<Vec3f>* vertex_normals = nullptr;
  /// Weighting of face normals when the normals come from the mesh (mesh estimators).
  NormalWeights normal_weights = NormalWeights::max;
  /// Batagelo estimator: the weight of each neighbour in the one-pass tensor's least squares (the
  /// derivative tensor's fit is unweighted either way). Ignored by the other estimators.
  NeighbourWeights batagelo_weights = NeighbourWeights::uniform;
  /// Radius, in world units, of the hemisphere the ambient occlusion integrates over (Griffin et
  /// al. section 3.7): curvatures are multiplied by it before the polynomial is evaluated, so a
  /// larger value darkens concave regions more.
  float ao_scale = 1.0f;
  /// The AO array's method (ao/method.h). griffin (the default) is every estimator's own
  /// polynomial at ao_scale; any other is computed by estimate_field's last step, apply_ao
  /// (ao::compute at ao_scale: the ray casts read the VolumeSource's volume).
  ao::Method ao_method = ao::Method::griffin;
  /// ao_method hattori: the umbilic mean rho (k1 + k2) / 2 (ao::Options::hattori_half).
  bool hattori_half = false;
  /// One piece of a surface divided among processes (core/surface_piece.h; dist/), or nullptr
  /// (the default): the whole surface. Only the volume estimator needs it (its automatic scale
  /// and weak-gradient threshold are the whole surface's); the mesh estimators see everything
  /// they need in the piece's margin. The pointee must outlive the call; collective.
  const SurfacePiece* piece = nullptr;
};

}  // namespace isocurv::curvature
