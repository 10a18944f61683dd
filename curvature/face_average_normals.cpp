#include "curvature/face_average_normals.h"

#include "curvature/detail/local_geometry.h"

namespace isocurv::curvature {

std::vector<Vec3f> face_average_normals(const Mesh& mesh) {
  const std::vector<detail::V3> n =
      detail::vertex_normals(mesh, Options{}, detail::NormalSource::uniform);
  std::vector<Vec3f> out(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) out[i] = detail::to_f3(n[i]);
  return out;
}

}  // namespace isocurv::curvature
