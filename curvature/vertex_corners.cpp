#include "curvature/vertex_corners.h"

namespace isocurv::curvature {

void build_vertex_corners(const Mesh& mesh, VertexCorners& out) {
  const std::size_t nv = mesh.positions.size(), nf = mesh.triangles.size();
  auto repeated = [](const Tri& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; };
  // Count each vertex's corners, then turn the counts into each row's start (exclusive scan).
  out.offsets.assign(nv + 1, 0);
  for (const Tri& t : mesh.triangles)
    if (!repeated(t)) ++out.offsets[t[0]], ++out.offsets[t[1]], ++out.offsets[t[2]];
  std::uint32_t start = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::uint32_t count = out.offsets[v];
    out.offsets[v] = start;
    start += count;
  }
  out.offsets[nv] = start;
  // Place the corners in triangle order; offsets[v] advances to the start of row v + 1.
  out.corners.resize(start);
  for (std::size_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.triangles[f];
    if (repeated(t)) continue;
    for (std::uint32_t j = 0; j < 3; ++j)
      out.corners[out.offsets[t[j]]++] = std::uint32_t(3 * f + j);
  }
  // Shift back: each row's start is the previous row's advanced cursor.
  for (std::size_t v = nv; v > 0; --v) out.offsets[v] = out.offsets[v - 1];
  out.offsets[0] = 0;
}

}  // namespace isocurv::curvature
