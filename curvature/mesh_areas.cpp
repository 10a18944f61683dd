#include "curvature/mesh_areas.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace isocurv::curvature {
namespace {

int next(int j) { return j == 2 ? 0 : j + 1; }
int prev(int j) { return j == 0 ? 2 : j - 1; }
bool repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

using P3 = std::array<double, 3>;
P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

}  // namespace

std::array<double, 3> mixed_corner_areas(const std::array<P3, 3>& p) {
  const P3 e[3] = {sub(p[2], p[1]), sub(p[0], p[2]), sub(p[1], p[0])};  // e[j] is opposite corner j
  const P3 c = cross(e[0], e[1]);
  const double area = 0.5 * std::sqrt(dot(c, c));
  if (!(area > 0)) return {0, 0, 0};
  const double l2[3] = {dot(e[0], e[0]), dot(e[1], e[1]), dot(e[2], e[2])};
  for (int j = 0; j < 3; ++j)
    if (l2[j] > l2[next(j)] + l2[prev(j)]) {  // obtuse at corner j
      std::array<double, 3> a{area / 4, area / 4, area / 4};
      a[j] = area / 2;
      return a;
    }
  double w[3];  // circumcentre barycentrics, up to a common factor (their sum is 16 area^2)
  for (int j = 0; j < 3; ++j) w[j] = l2[j] * (l2[next(j)] + l2[prev(j)] - l2[j]);
  const double sum = w[0] + w[1] + w[2];
  if (!(sum > 0)) return {area / 3, area / 3, area / 3};  // rounding on a needle
  const double scale = area / (2 * sum);
  return {scale * (w[1] + w[2]), scale * (w[2] + w[0]), scale * (w[0] + w[1])};
}

std::vector<float> mixed_vertex_areas(const Mesh& mesh) {
  std::vector<double> area(mesh.positions.size(), 0.0);
  for (const Tri& t : mesh.triangles) {
    if (repeated_index(t)) continue;
    std::array<P3, 3> p;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) p[j][k] = mesh.positions[t[j]][k];
    const std::array<double, 3> a = mixed_corner_areas(p);
    for (int j = 0; j < 3; ++j) area[t[j]] += a[j];
  }
  return std::vector<float>(area.begin(), area.end());
}

std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh) {
  // Every edge use as (low, high), bucketed by its low end (a counting sort: linear time); an edge
  // used once is on the boundary. Buckets hold a vertex's few edges towards higher indices.
  const std::size_t nv = mesh.positions.size();
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const Tri& t : mesh.triangles)
    if (!repeated_index(t))
      for (int j = 0; j < 3; ++j) ++start[std::min(t[j], t[next(j)]) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> high(start[nv]), fill(start.begin(), start.end() - 1);
  for (const Tri& t : mesh.triangles)
    if (!repeated_index(t))
      for (int j = 0; j < 3; ++j) {
        const auto [lo, hi] = std::minmax(t[j], t[next(j)]);
        high[fill[lo]++] = hi;
      }
  std::vector<std::uint8_t> boundary(nv, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    const auto first = high.begin() + start[v], last = high.begin() + start[v + 1];
    std::sort(first, last);
    for (auto i = first; i != last;) {
      auto j = i + 1;
      while (j != last && *j == *i) ++j;
      if (j - i == 1) boundary[v] = boundary[*i] = 1;
      i = j;
    }
  }
  return boundary;
}

}  // namespace isocurv::curvature
