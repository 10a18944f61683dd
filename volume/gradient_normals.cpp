#include "volume/gradient_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/mesh_measures.h"

namespace isocurv::volume {
namespace {

/// Index-space gradient sampling with optional clamping to a dense volume's domain.
struct GradientSampler {
  openvdb::FloatGrid::ConstAccessor acc;
  bool clamp;
  openvdb::Coord lo, hi;

  int cx(int v, int a) const { return clamp ? std::min(std::max(v, lo[a]), hi[a]) : v; }
  float value(int x, int y, int z) { return acc.getValue(openvdb::Coord(x, y, z)); }

  /// Central (or, at the domain border, one-sided) difference at voxel (x, y, z).
  openvdb::Vec3d at(int x, int y, int z) {
    openvdb::Vec3d g;
    const int c[3] = {x, y, z};
    for (int a = 0; a < 3; ++a) {
      int p[3] = {c[0], c[1], c[2]}, m[3] = {c[0], c[1], c[2]};
      p[a] = cx(c[a] + 1, a);
      m[a] = cx(c[a] - 1, a);
      const int span = p[a] - m[a];
      g[a] = span == 0 ? 0.0
                       : (double(value(p[0], p[1], p[2])) - double(value(m[0], m[1], m[2]))) / span;
    }
    return g;
  }

  /// Trilinear interpolation of the voxel gradients around index-space point q: the central
  /// differences at the 8 voxels around q, from the 32 samples they use (each read once; `at` per
  /// corner would read 48), summed in the same order as `at`, so the result is the same.
  openvdb::Vec3d interpolate(const openvdb::Vec3d& q) {
    openvdb::Vec3d qc = q;
    if (clamp)
      for (int a = 0; a < 3; ++a) qc[a] = std::min(std::max(qc[a], double(lo[a])), double(hi[a]));
    const int base[3] = {int(std::floor(qc[0])), int(std::floor(qc[1])), int(std::floor(qc[2]))};
    const double f[3] = {qc[0] - base[0], qc[1] - base[1], qc[2] - base[2]};
    // Per axis the coordinates cx(base - 1) .. cx(base + 2): every corner cx(base + i) and its
    // neighbours cx(corner -+ 1) that `at` reads are among them (q is clamped into the domain).
    int coord[3][4];
    for (int a = 0; a < 3; ++a)
      for (int t = 0; t < 4; ++t) coord[a][t] = cx(base[a] + t - 1, a);
    // Where coordinate c sits in its axis's row: the corners' slots 1 and 2 first, so a
    // neighbour that clamping folds onto a corner reads the corner's sample.
    auto slot = [&](int a, int c) {
      for (int t : {1, 2, 0, 3})
        if (coord[a][t] == c) return t;
      return 1;  // not reached: every coordinate `at` reads is in the row
    };
    // The 32 samples: the 2x2x2 corners (slots 1..2 on every axis) and those one step beyond a
    // corner along one axis (slot 0 or 3 on exactly one axis).
    float v[4][4][4];
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
          if ((i % 3 == 0) + (j % 3 == 0) + (k % 3 == 0) <= 1)
            v[k][j][i] = value(coord[0][i], coord[1][j], coord[2][k]);
    openvdb::Vec3d g(0.0);
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const double w = (i ? f[0] : 1 - f[0]) * (j ? f[1] : 1 - f[1]) * (k ? f[2] : 1 - f[2]);
          if (w == 0) continue;
          const int corner[3] = {1 + i, 1 + j, 1 + k};
          openvdb::Vec3d d;
          for (int a = 0; a < 3; ++a) {  // `at`'s central (or one-sided) difference
            const int c = coord[a][corner[a]], up = cx(c + 1, a), down = cx(c - 1, a);
            int p[3] = {corner[0], corner[1], corner[2]}, m[3] = {corner[0], corner[1], corner[2]};
            p[a] = slot(a, up);
            m[a] = slot(a, down);
            const int span = up - down;
            d[a] = span == 0 ? 0.0 : (double(v[p[2]][p[1]][p[0]]) - double(v[m[2]][m[1]][m[0]])) / span;
          }
          g += w * d;
        }
    return g;
  }
};

// Outward gradients (world space, not normalised; the sign applied) at world positions; zero
// where not finite.
std::vector<openvdb::Vec3d> outward_gradients(const Volume& volume,
                                              const Positions& world_positions) {
  std::vector<openvdb::Vec3d> out(world_positions.size(), openvdb::Vec3d(0.0));
  if (!volume.grid || world_positions.empty()) return out;
  const openvdb::FloatGrid& grid = *volume.grid;
  const openvdb::math::Transform& xform = grid.transform();
  const openvdb::math::MapBase::ConstPtr map = xform.baseMap();
  const double sign = volume.inside == Inside::Above ? -1.0 : 1.0;
  const bool clamp = volume.dense && !volume.domain.empty();

  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, world_positions.size(), 512),
      [&](const tbb::blocked_range<std::size_t>& r) {
        GradientSampler s{grid.getConstAccessor(), clamp, volume.domain.min(), volume.domain.max()};
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Vec3f& p = world_positions[i];
          const openvdb::Vec3d q = xform.worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
          const openvdb::Vec3d g = sign * map->applyIJT(s.interpolate(q), q);
          if (std::isfinite(g.length())) out[i] = g;
        }
      });
  return out;
}

// g / |g| as floats; zero for a zero vector.
Vec3f unit(const openvdb::Vec3d& g) {
  const double len = g.length();
  if (!(len > 0)) return {0, 0, 0};
  return {float(g.x() / len), float(g.y() / len), float(g.z() / len)};
}

// Cap vertices lie outside the domain's box by a 1/1024 voxel (the mesher's smallest edge
// fraction) or less; vertices of the surface itself lie inside it or on it. This tolerance, in
// voxels, tells a vertex on the box face (rounding) from one beyond it.
constexpr double kOnBox = 1e-4;
constexpr double kCapDepth = 0.01;  // deeper than any cap vertex, far shallower than a voxel

// Gives the cap vertices of `mesh` the outward normal of the box faces they lie beyond.
void cap_normals(const Volume& volume, const Mesh& mesh, MeshNormals& r) {
  const openvdb::math::Transform& xform = volume.grid->transform();
  const openvdb::math::MapBase::ConstPtr map = xform.baseMap();
  const openvdb::Coord lo = volume.domain.min(), hi = volume.domain.max();
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    const openvdb::Vec3d q = xform.worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
    openvdb::Vec3d n(0.0);
    bool inside_slab = true;
    for (int k = 0; k < 3; ++k) {
      const double below = lo[k] - q[k], above = q[k] - hi[k];
      if (below > kOnBox) n[k] = -1;
      if (above > kOnBox) n[k] = 1;
      inside_slab = inside_slab && below < kCapDepth && above < kCapDepth;
    }
    if (n == openvdb::Vec3d(0.0) || !inside_slab) continue;
    r.normals[i] = unit(map->applyIJT(n, q));  // index-space face normals to world space
    ++r.caps;
  }
}

}  // namespace

std::vector<Vec3f> gradient_normals(const Volume& volume, const Positions& world_positions) {
  const std::vector<openvdb::Vec3d> g = outward_gradients(volume, world_positions);
  std::vector<Vec3f> normals(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) normals[i] = unit(g[i]);
  return normals;
}

MeshNormals gradient_normals_for_mesh(const Volume& volume, const Mesh& mesh, bool caps) {
  MeshNormals r;
  const std::vector<openvdb::Vec3d> g = outward_gradients(volume, mesh.positions);
  const std::vector<Vec3f> faces = area_weighted_normals(mesh);
  std::vector<double> lengths;
  lengths.reserve(g.size());
  for (const openvdb::Vec3d& v : g)
    if (v.length() > 0) lengths.push_back(v.length());
  double weak_below = 0;
  if (!lengths.empty()) {
    auto mid = lengths.begin() + lengths.size() / 2;
    std::nth_element(lengths.begin(), mid, lengths.end());
    weak_below = kWeakGradientFraction * *mid;
  }
  r.normals.resize(g.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    const openvdb::Vec3d a(faces[i][0], faces[i][1], faces[i][2]);
    const bool weak = !(g[i].length() > weak_below);
    const bool opposed = !weak && g[i].dot(a) <= 0;
    if (a.length() > 0 && (weak || opposed)) {
      r.normals[i] = unit(a);
      ++(weak ? r.weak : r.opposed);
    } else {
      r.normals[i] = unit(g[i]);
    }
  }
  if (caps && volume.dense && !volume.domain.empty() && volume.grid) cap_normals(volume, mesh, r);
  return r;
}

}  // namespace isocurv::volume
