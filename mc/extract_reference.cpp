#include "mc/extract_reference.h"

#include <map>

#include "mc/case_table.h"
#include "mc/edge_key.h"
#include "mc/frame.h"
#include "mc/snap_vertices.h"
#include "mc/triangle_quality.h"

namespace isocurv::mc {

Mesh extract_reference(const volume::Volume& v, float isovalue, const Options& options) {
  const Frame f = make_frame(v, isovalue, options);
  const CaseTable& table = case_table();
  Mesh mesh;
  if (f.cells.empty()) return mesh;
  auto acc = v.grid->getConstAccessor();
  std::map<std::uint64_t, std::uint32_t> vertex_of_edge;
  std::vector<SnapCandidate> snaps;

  auto vertex = [&](const openvdb::Coord& cell, int edge, const float s[8]) -> std::uint32_t {
    const int lo = kEdgeLow[edge], axis = kEdgeAxis[edge];
    const openvdb::Coord a = cell + openvdb::Coord(kCornerX[lo], kCornerY[lo], kCornerZ[lo]);
    const openvdb::Coord k = a - f.key_origin;
    const std::uint64_t key = edge_key(k.x(), k.y(), k.z(), axis);
    auto it = vertex_of_edge.find(key);
    if (it != vertex_of_edge.end()) return it->second;
    const float t = edge_fraction(s[lo], s[kEdgeHigh[edge]]);
    double p[3] = {double(a.x()), double(a.y()), double(a.z())};
    p[axis] += t;
    Vec3f w;
    for (int r = 0; r < 3; ++r)
      w[r] = static_cast<float>(f.world[r * 4 + 0] * p[0] + f.world[r * 4 + 1] * p[1] +
                                f.world[r * 4 + 2] * p[2] + f.world[r * 4 + 3]);
    const auto index = static_cast<std::uint32_t>(mesh.positions.size());
    if (t < options.snap) snaps.push_back({key, index});
    if (t > 1.0f - options.snap) snaps.push_back({key | kSnapUpper, index});
    mesh.positions.push_back(w);
    if (options.keep_edge_keys) mesh.edge_keys.push_back(key);
    vertex_of_edge.emplace(key, index);
    return index;
  };

  for (int z = f.cells.min().z(); z <= f.cells.max().z(); ++z)
    for (int y = f.cells.min().y(); y <= f.cells.max().y(); ++y)
      for (int x = f.cells.min().x(); x <= f.cells.max().x(); ++x) {
        const openvdb::Coord cell(x, y, z);
        float s[8];
        int index = 0;
        for (int c = 0; c < 8; ++c) {
          const openvdb::Coord ijk = cell + openvdb::Coord(kCornerX[c], kCornerY[c], kCornerZ[c]);
          s[c] = f.signed_value(ijk, acc.getValue(ijk));
          if (s[c] > 0) index |= 1 << c;
        }
        for (int t = 0; t < table.triangle_count[index]; ++t) {
          Tri tri;
          for (int j = 0; j < 3; ++j) tri[j] = vertex(cell, table.edges[index][3 * t + j], s);
          mesh.triangles.push_back(tri);
        }
      }
  snap_vertices(mesh, std::move(snaps), f, kSnapMinArea, options.snap);
  return mesh;
}

}  // namespace isocurv::mc
