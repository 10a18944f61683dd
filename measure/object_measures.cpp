#include "measure/object_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/error.h"
#include "core/mesh_measures.h"

namespace isocurv::measure {
namespace {

constexpr double kTwoPi = 6.283185307179586;

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root is the lowest id
  }
};

bool usable(const Tri& t, std::size_t nv) {
  return t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
}

}  // namespace

double ObjectMeasures::gauss_bonnet_gap() const {
  if (!closed) return std::numeric_limits<double>::quiet_NaN();
  return (integral_K - kTwoPi * double(euler)) / (kTwoPi * std::max(1.0, std::abs(double(euler))));
}

std::vector<ObjectMeasures> object_measures(const Mesh& mesh, const curvature::CurvatureField& field) {
  const std::size_t nv = mesh.positions.size();
  if (field.H.size() != nv || field.K.size() != nv)
    throw Error("measure: the curvature field has " + std::to_string(field.H.size()) + " H and " +
                std::to_string(field.K.size()) + " K values for " + std::to_string(nv) + " vertices");
  UnionFind uf(nv);
  std::vector<std::uint64_t> edges;  // (lo, hi) packed, one per triangle side
  edges.reserve(3 * mesh.triangles.size());
  std::vector<double> third_area;  // a third of the adjacent triangles' areas (no Area array)
  const bool have_area = field.area.size() == nv;
  if (!have_area) third_area.assign(nv, 0.0);
  for (const Tri& t : mesh.triangles) {
    if (!usable(t, nv)) continue;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      uf.unite(a, b);
      edges.push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
    if (!have_area) {
      const auto n = triangle_area_vector(mesh, t);
      const double a = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 3;
      for (std::uint32_t i : t) third_area[i] += a;
    }
  }
  // Components in order of their lowest vertex (the union-find root), vertices that some usable
  // triangle uses.
  std::vector<std::uint32_t> index(nv, ~0u);
  std::vector<ObjectMeasures> out;
  std::vector<char> used(nv, 0);
  for (const Tri& t : mesh.triangles)
    if (usable(t, nv))
      for (std::uint32_t i : t) used[i] = 1;
  for (std::uint32_t i = 0; i < nv; ++i) {
    if (!used[i]) continue;
    const std::uint32_t root = uf.find(i);
    if (index[root] == ~0u) {
      index[root] = std::uint32_t(out.size());
      ObjectMeasures m;
      m.first_vertex = i;
      m.box = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
      out.push_back(m);
    }
    ObjectMeasures& m = out[index[root]];
    ++m.vertices;
    const double a = have_area ? double(field.area[i]) : third_area[i];
    const bool flagged = field.unreliable.size() == nv && field.unreliable[i];
    m.unmeasured += flagged;
    if (!flagged && std::isfinite(field.H[i]) && std::isfinite(field.K[i])) {
      m.integral_H += double(field.H[i]) * a;
      m.integral_K += double(field.K[i]) * a;
    }
    for (int c = 0; c < 3; ++c) {
      m.box[2 * c] = std::min(m.box[2 * c], double(mesh.positions[i][c]));
      m.box[2 * c + 1] = std::max(m.box[2 * c + 1], double(mesh.positions[i][c]));
    }
  }
  for (const Tri& t : mesh.triangles) {
    if (!usable(t, nv)) continue;
    ObjectMeasures& m = out[index[uf.find(t[0])]];
    ++m.triangles;
    const auto n = triangle_area_vector(mesh, t);
    m.area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    m.volume += signed_volume_term(mesh, t, mesh.positions[m.first_vertex]);
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    ObjectMeasures& m = out[index[uf.find(std::uint32_t(edges[i] >> 32))]];
    ++m.edges;
    if (j - i == 1) ++m.boundary_edges;
    i = j;
  }
  for (ObjectMeasures& m : out) {
    m.closed = m.boundary_edges == 0;
    m.euler = (long long)m.vertices - (long long)m.edges + (long long)m.triangles;
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const ObjectMeasures& a, const ObjectMeasures& b) { return a.area > b.area; });
  return out;
}

ObjectMeasures total(const std::vector<ObjectMeasures>& objects) {
  ObjectMeasures t;
  t.closed = true;
  t.box = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (const ObjectMeasures& m : objects) {
    t.vertices += m.vertices, t.triangles += m.triangles, t.edges += m.edges;
    t.boundary_edges += m.boundary_edges;
    t.closed = t.closed && m.closed;
    t.area += m.area, t.volume += m.volume;
    t.integral_H += m.integral_H, t.integral_K += m.integral_K;
    t.euler += m.euler;
    t.unmeasured += m.unmeasured;
    for (int c = 0; c < 3; ++c) {
      t.box[2 * c] = std::min(t.box[2 * c], m.box[2 * c]);
      t.box[2 * c + 1] = std::max(t.box[2 * c + 1], m.box[2 * c + 1]);
    }
  }
  return t;
}

}  // namespace isocurv::measure
