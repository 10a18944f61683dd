#include "core/vec3.h"
#include "curvature/mesh_areas.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace isocurv::curvature {
namespace {

int next(int j) { return j == 2 ? 0 : j + 1; }
int prev(int j) { return j == 0 ? 2 : j - 1; }
bool repeated_index(const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

using P3 = std::array<double, 3>;
using vec3::sub;
using vec3::dot;
using vec3::cross;

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

std::vector<float> mixed_vertex_areas(const Mesh& mesh, const VertexCorners& corners) {
  // Every corner's area (parallel over triangles), then each vertex's corners summed in
  // increasing order (parallel over vertices): the order a serial pass over the triangles takes,
  // so the result does not depend on the threads.
  const std::size_t nt = mesh.triangles.size(), nv = mesh.positions.size();
  std::vector<float> corner(3 * nt, 0.0f);  // float: half the memory to touch; summed in double
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nt, 4096), [&](const auto& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) {
      const Tri& t = mesh.triangles[f];
      if (repeated_index(t)) continue;
      std::array<P3, 3> p;
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) p[j][k] = mesh.positions[t[j]][k];
      const std::array<double, 3> a = mixed_corner_areas(p);
      for (int j = 0; j < 3; ++j) corner[3 * f + j] = float(a[j]);
    }
  });
  std::vector<float> area(nv);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const auto& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      double sum = 0;
      for (std::uint32_t c = corners.offsets[v]; c < corners.offsets[v + 1]; ++c)
        sum += corner[corners.corners[c]];
      area[v] = float(sum);
    }
  });
  return area;
}

std::vector<float> mixed_vertex_areas(const Mesh& mesh) {
  VertexCorners corners;
  build_vertex_corners(mesh, corners);
  return mixed_vertex_areas(mesh, corners);
}

std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh, const VertexCorners& corners) {
  // An edge (v, w) used by one triangle puts w once among the neighbours v's triangles list
  // (each triangle through the edge lists w once: a triangle without a repeated index has w
  // either after or before v, not both). The lists are short: counting by direct comparison
  // beats sorting. Parallel over vertices, each writing its own flag.
  const std::size_t nv = mesh.positions.size();
  std::vector<std::uint8_t> boundary(nv, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const auto& r) {
    std::vector<std::uint32_t> around;
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      around.clear();
      for (std::uint32_t c = corners.offsets[v]; c < corners.offsets[v + 1]; ++c) {
        const Tri& t = mesh.triangles[corners.corners[c] / 3];
        const int j = int(corners.corners[c] % 3);
        around.push_back(t[next(j)]);
        around.push_back(t[prev(j)]);
      }
      const std::size_t k = around.size();
      for (std::size_t i = 0; i < k && !boundary[v]; ++i) {
        std::size_t same = 0;
        for (std::size_t m = 0; m < k; ++m) same += around[m] == around[i];
        if (same == 1) boundary[v] = 1;
      }
    }
  });
  return boundary;
}

std::vector<std::uint8_t> boundary_vertices(const Mesh& mesh) {
  VertexCorners corners;
  build_vertex_corners(mesh, corners);
  return boundary_vertices(mesh, corners);
}

}  // namespace isocurv::curvature
