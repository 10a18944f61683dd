#include "features/detail/ball_samples.h"

#include <cmath>

namespace isocurv::features::detail {

BallSums ball_sums(const Mesh &mesh, const MeshGraph &graph,
                   const std::vector<Vec3f> &normals,
                   const std::vector<float> &area, std::uint32_t v, double r,
                   std::vector<std::uint32_t> &stamp, std::uint32_t mark,
                   std::vector<std::uint32_t> &queue) {
  BallSums s;
  const Vec3f &p = mesh.positions[v];
  const Vec3f &n = normals[v];
  const double r2 = r * r;
  queue.clear();
  queue.push_back(v);
  stamp[v] = mark;
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t q = queue[head];
    const double a = area[q];
    s.area += a;
    if (graph.on_boundary[q])
      s.touches_boundary = true;
    if (q != v) {
      const Vec3f &x = mesh.positions[q];
      const double d[3] = {double(x[0]) - p[0], double(x[1]) - p[1],
                           double(x[2]) - p[2]};
      const double dist2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const double along = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
      s.height += a * along;
      if (dist2 > 0) {
        const Vec3f &m = normals[q];
        const double dn[3] = {double(n[0]) - m[0], double(n[1]) - m[1],
                              double(n[2]) - m[2]};
        s.bending +=
            a * (dn[0] * dn[0] + dn[1] * dn[1] + dn[2] * dn[2]) / dist2;
        s.horizon += a * 0.5 * (1 - along / std::sqrt(dist2));
        s.horizon_area += a;
      }
    }
    for (std::uint32_t k = graph.vv_start[q]; k < graph.vv_start[q + 1]; ++k) {
      const std::uint32_t w = graph.vv[k];
      if (stamp[w] == mark)
        continue;
      const Vec3f &x = mesh.positions[w];
      const double d0 = double(x[0]) - p[0], d1 = double(x[1]) - p[1],
                   d2 = double(x[2]) - p[2];
      if (d0 * d0 + d1 * d1 + d2 * d2 > r2)
        continue; // outside: neither sampled nor expanded
      stamp[w] = mark;
      queue.push_back(w);
    }
  }
  return s;
}

} // namespace isocurv::features::detail
