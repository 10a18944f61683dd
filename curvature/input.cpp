#include "curvature/input.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/error.h"

namespace isocurv::curvature {

void check_triangles(const Triangles& triangles, std::size_t nv) {
  const std::size_t nf = triangles.size();
  if (nv > std::numeric_limits<std::uint32_t>::max() ||
      nf > std::numeric_limits<std::uint32_t>::max() / 3)
    throw Error("curvature: mesh too large (" + std::to_string(nv) + " vertices, " +
                std::to_string(nf) + " triangles; at most 2^32 - 1 vertices and corners)");
  for (std::size_t f = 0; f < nf; ++f) {
    const Tri& t = triangles[f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw Error("curvature: triangle " + std::to_string(f) + " refers to vertex " +
                  std::to_string(std::max({t[0], t[1], t[2]})) + " but the mesh has " +
                  std::to_string(nv) + " vertices");
  }
}

void check_positions(const Positions& positions) {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3f& p = positions[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error("curvature: vertex " + std::to_string(i) + " has a non-finite coordinate");
  }
}

void check_input(const Mesh& mesh, const Options& options) {
  const std::size_t nv = mesh.positions.size();
  const std::size_t nf = mesh.triangles.size();
  if (nv > std::numeric_limits<std::uint32_t>::max() ||
      nf > std::numeric_limits<std::uint32_t>::max() / 3)
    check_triangles(mesh.triangles, nv);  // the size error first, before any per-vertex check
  check_positions(mesh.positions);
  check_triangles(mesh.triangles, nv);
  check_options(options, nv);
}

void check_options(const Options& options, std::size_t nv) {
  if (options.vertex_normals && options.vertex_normals->size() != nv)
    throw Error("curvature: " + std::to_string(options.vertex_normals->size()) +
                " vertex normals given for a mesh of " + std::to_string(nv) + " vertices");
  if (!std::isfinite(options.ao_scale))
    throw Error("curvature: ao_scale must be finite");
}

}  // namespace isocurv::curvature
