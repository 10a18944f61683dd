#include "curvature/ao_scale.h"

#include "core/mesh_measures.h"

namespace isocurv::curvature {

float default_ao_scale(const Mesh& mesh) {
  return mesh.triangles.empty() ? 1.0f : static_cast<float>(4 * mean_edge_length(mesh));
}

}  // namespace isocurv::curvature
