#include "curvature/ao_scale.h"

#include <cmath>

#include "core/mesh_measures.h"

namespace isocurv::curvature {

float default_ao_scale(const Mesh& mesh, const SurfacePiece* piece) {
  if (!piece) return mesh.triangles.empty() ? 1.0f : static_cast<float>(4 * mean_edge_length(mesh));
  double sum = 0;
  std::uint64_t edges = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!piece->owned_triangles[t]) continue;
    for (int e = 0; e < 3; ++e) {
      const Vec3f& a = mesh.positions[mesh.triangles[t][e]];
      const Vec3f& b = mesh.positions[mesh.triangles[t][(e + 1) % 3]];
      const double dx = double(b[0]) - a[0], dy = double(b[1]) - a[1], dz = double(b[2]) - a[2];
      sum += std::sqrt(dx * dx + dy * dy + dz * dz);
    }
    edges += 3;
  }
  const std::vector<double> all = piece->all({sum, double(edges)});
  double total = 0, count = 0;
  for (std::size_t i = 0; i + 1 < all.size(); i += 2) total += all[i], count += all[i + 1];
  return count == 0 ? 1.0f : static_cast<float>(4 * (total / count));
}

}  // namespace isocurv::curvature
