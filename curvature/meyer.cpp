#include "curvature/meyer.h"

#include <cmath>
#include <vector>

#include "curvature/detail/local_geometry.h"
#include "curvature/input.h"

namespace isocurv::curvature {
namespace {

using detail::V3;

// Corner j's angle and cotangent in the triangle p; false for a degenerate corner.
bool corner_angle(const V3 p[3], int j, double& angle, double& cot) {
  const V3 a = p[(j + 1) % 3] - p[j], b = p[(j + 2) % 3] - p[j];
  const double sin = a.cross(b).norm(), cos = a.dot(b);
  if (!(sin > 0)) return false;
  angle = std::atan2(sin, cos);
  cot = cos / sin;
  return true;
}

}  // namespace

CurvatureField estimate_meyer_reference(const Mesh& mesh, const Options& options) {
  check_input(mesh, options);
  const std::size_t nv = mesh.positions.size();
  const std::vector<V3> normal = detail::vertex_normals(mesh, options);
  CurvatureField out = detail::allocate_field(mesh, /*with_directions=*/false);

  // Laplace-Beltrami vector sum (cot a + cot b)(p_i - p_j) and angle sums.
  std::vector<V3> laplace(nv, V3::Zero());
  std::vector<double> angles(nv, 0);
  for (const Tri& t : mesh.triangles) {
    if (detail::repeated_index(t)) continue;
    const V3 p[3] = {detail::to_v3(mesh.positions[t[0]]), detail::to_v3(mesh.positions[t[1]]),
                     detail::to_v3(mesh.positions[t[2]])};
    double angle[3], cot[3];
    if (!corner_angle(p, 0, angle[0], cot[0]) || !corner_angle(p, 1, angle[1], cot[1]) ||
        !corner_angle(p, 2, angle[2], cot[2]))
      continue;  // zero area: no angles, no area
    for (int j = 0; j < 3; ++j) {
      angles[t[j]] += angle[j];
      // The edge opposite corner j joins corners a and b.
      const int a = (j + 1) % 3, b = (j + 2) % 3;
      laplace[t[a]] += cot[j] * (p[a] - p[b]);
      laplace[t[b]] += cot[j] * (p[b] - p[a]);
    }
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const double area = out.area[i];
    double h = 0, k = 0;
    if (area > 0) {
      h = laplace[i].norm() / (4 * area);
      if (laplace[i].dot(normal[i]) < 0) h = -h;
      k = ((out.boundary[i] ? M_PI : 2 * M_PI) - angles[i]) / area;
      if (out.boundary[i]) out.unreliable[i] = 1;  // a one-sided ring: neither is a curvature
    } else {
      out.unreliable[i] = 1;
    }
    const double root = std::sqrt(std::max(0.0, h * h - k));
    detail::set_vertex(out, i, normal[i], h + root, h - root, options.ao_scale);
    out.H[i] = float(h), out.K[i] = float(k);
  }
  return out;
}

}  // namespace isocurv::curvature
