#pragma once
// Options of the curvature estimator (curvature::estimate and curvature::estimate_reference).
#include <vector>

#include "core/mesh.h"

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

struct Options {
  /// Per-vertex outward normals supplied from outside (e.g. the volume gradient), one per mesh
  /// vertex; they need not be unit length (they are normalised). A zero or non-finite entry falls
  /// back to the mesh normal of that vertex. nullptr (the default): normals from the mesh faces.
  /// The pointee must outlive the call.
  const std::vector<Vec3f>* vertex_normals = nullptr;
  /// Weighting of face normals when the normals come from the mesh.
  NormalWeights normal_weights = NormalWeights::max;
  /// Radius, in world units, of the hemisphere the ambient occlusion integrates over (Griffin et
  /// al. section 3.7): curvatures are multiplied by it before the polynomial is evaluated, so a
  /// larger value darkens concave regions more.
  float ao_scale = 1.0f;
};

}  // namespace isocurv::curvature
