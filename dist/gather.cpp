#include "dist/gather.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"
#include "io/field_arrays.h"

namespace isocurv::dist {

void gather_mesh(const World& world, const Piece& piece, const curvature::CurvatureField* field, Mesh& mesh_out,
                 curvature::CurvatureField& whole) {
  // Each rank: its owned vertices (global id, position, field values) and owned triangles (as
  // global-id triples), packed.
  std::vector<std::uint32_t> owned;
  for (std::uint32_t v = 0; v < piece.point_ghost.size(); ++v)
    if (!piece.point_ghost[v]) owned.push_back(v);
  std::vector<char> bytes;
  auto put = [&](const void* data, std::size_t n) {
    const char* c = static_cast<const char*>(data);
    bytes.insert(bytes.end(), c, c + n);
  };
  const std::uint64_t nv = owned.size(), nt = piece.owned_triangles;
  put(&nv, sizeof nv);
  put(&nt, sizeof nt);
  for (std::uint32_t v : owned) put(&piece.global_ids[v], sizeof(std::int64_t));
  for (std::uint32_t v : owned) put(&piece.mesh.positions[v], sizeof(Vec3f));
  for (std::size_t t = 0; t < piece.owned_triangles; ++t)
    for (std::uint32_t v : piece.mesh.triangles[t]) put(&piece.global_ids[v], sizeof(std::int64_t));
  curvature::CurvatureField owned_field;
  if (field) {
    owned_field = io::select_vertices(*field, owned);
    io::for_each_array(owned_field, [&](const char*, const auto& a) {
      const std::uint64_t n = a.size();
      put(&n, sizeof n);
      put(a.data(), a.size() * sizeof(a[0]));
    });
  }
  const auto all = world.gather(bytes);
  if (world.rank() != 0) return;
  {
    // Concatenate in rank order, then order the vertices by global id.
    std::vector<std::int64_t> ids;
    Mesh mesh;
    std::vector<std::int64_t> tri_ids;
    curvature::CurvatureField merged = owned_field;  // the arrays' layout (names, extras)
    if (field) io::for_each_array(merged, [&](const char*, auto& a) { a.clear(); });
    merged.surface_points.clear();  // not sent: the volume estimator does not run distributed
    for (const auto& b : all) {
      const char* at = b.data();
      auto get = [&](void* out, std::size_t n) {
        std::memcpy(out, at, n);
        at += n;
      };
      std::uint64_t n = 0, m = 0;
      get(&n, sizeof n);
      get(&m, sizeof m);
      const std::size_t i0 = ids.size(), t0 = tri_ids.size();
      ids.resize(i0 + n);
      get(ids.data() + i0, n * sizeof(std::int64_t));
      mesh.positions.resize(i0 + n);
      get(mesh.positions.data() + i0, n * sizeof(Vec3f));
      tri_ids.resize(t0 + 3 * m);
      get(tri_ids.data() + t0, 3 * m * sizeof(std::int64_t));
      if (field)
        io::for_each_array(merged, [&](const char*, auto& a) {
          std::uint64_t k = 0;
          get(&k, sizeof k);
          const std::size_t a0 = a.size();
          a.resize(a0 + k);
          get(a.data() + a0, k * sizeof(a[0]));
        });
    }
    std::vector<std::uint32_t> order(ids.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return ids[a] < ids[b]; });
    Mesh out;
    out.positions.resize(order.size());
    std::vector<std::int64_t> sorted(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      out.positions[i] = mesh.positions[order[i]];
      sorted[i] = ids[order[i]];
    }
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw Error("two pieces both own a vertex (the pieces do not fit together)");
    auto index_of = [&](std::int64_t id) {
      const auto it = std::lower_bound(sorted.begin(), sorted.end(), id);
      if (it == sorted.end() || *it != id) throw Error("a triangle uses a vertex no piece owns");
      return std::uint32_t(it - sorted.begin());
    };
    out.triangles.resize(tri_ids.size() / 3);
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
      out.triangles[t] = {index_of(tri_ids[3 * t]), index_of(tri_ids[3 * t + 1]), index_of(tri_ids[3 * t + 2])};
    if (field) whole = io::select_vertices(merged, order);
    mesh_out = std::move(out);
  }
}


}  // namespace isocurv::dist
