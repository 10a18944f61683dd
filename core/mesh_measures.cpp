#include "core/mesh_measures.h"

#include <cmath>

namespace isocurv {

double mean_edge_length(const Mesh& mesh) {
  if (mesh.triangles.empty()) return 0;
  double sum = 0;
  for (const Tri& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const Vec3f& a = mesh.positions[t[e]];
      const Vec3f& b = mesh.positions[t[(e + 1) % 3]];
      const double dx = double(b[0]) - a[0], dy = double(b[1]) - a[1], dz = double(b[2]) - a[2];
      sum += std::sqrt(dx * dx + dy * dy + dz * dz);
    }
  return sum / (3.0 * static_cast<double>(mesh.triangles.size()));
}

}  // namespace isocurv
