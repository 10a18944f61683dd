#include "mc/triangle_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isocurv::mc {

TriangleQuality triangle_quality(const Mesh& mesh, double unit_area) {
  TriangleQuality q;
  q.unit_area = unit_area;
  const std::size_t nv = mesh.positions.size();
  const double small_below = kSmallAreaFraction * unit_area;
  const double degrees = 180.0 / std::acos(-1.0);
  double min_area = std::numeric_limits<double>::infinity(), min_angle = 180;
  for (const Tri& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) continue;
    ++q.triangles;
    double p[3][3];
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) p[c][k] = mesh.positions[t[c]][k];
    double smallest = 180, area = 0;
    for (int c = 0; c < 3; ++c) {
      const double* a = p[c];
      const double* b = p[(c + 1) % 3];
      const double* d = p[(c + 2) % 3];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const double v[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                           u[0] * v[1] - u[1] * v[0]};
      const double cross = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
      smallest = std::min(smallest, std::atan2(cross, dot) * degrees);
      if (c == 0) area = 0.5 * cross;
    }
    min_area = std::min(min_area, area);
    min_angle = std::min(min_angle, smallest);
    if (area < small_below) ++q.small;
    if (smallest < kThinAngleDegrees) ++q.thin;
  }
  if (q.triangles > 0) {
    q.min_area = min_area;
    q.min_angle = min_angle;
  } else {
    q.min_angle = 0;
  }
  return q;
}

double voxel_face_area(const volume::Volume& volume) {
  const openvdb::Vec3d s = volume.spacing();
  return std::pow(std::fabs(s[0] * s[1] * s[2]), 2.0 / 3.0);
}

}  // namespace isocurv::mc
