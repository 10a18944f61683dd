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
      g[a] = span == 0 ? 0.0 : (double(value(p[0], p[1], p[2])) - double(value(m[0], m[1], m[2]))) / span;
    }
    return g;
  }

  /// Trilinear interpolation of the voxel gradients around index-space point q.
  openvdb::Vec3d interpolate(const openvdb::Vec3d& q) {
    openvdb::Vec3d qc = q;
    if (clamp)
      for (int a = 0; a < 3; ++a) qc[a] = std::min(std::max(qc[a], double(lo[a])), double(hi[a]));
    const int x0 = int(std::floor(qc[0])), y0 = int(std::floor(qc[1])), z0 = int(std::floor(qc[2]));
    const double fx = qc[0] - x0, fy = qc[1] - y0, fz = qc[2] - z0;
    openvdb::Vec3d g(0.0);
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const double w = (i ? fx : 1 - fx) * (j ? fy : 1 - fy) * (k ? fz : 1 - fz);
          if (w == 0) continue;
          g += w * at(cx(x0 + i, 0), cx(y0 + j, 1), cx(z0 + k, 2));
        }
    return g;
  }
};

// Outward gradients (world space, not normalised; the sign applied) at world positions.
std::vector<Vec3f> outward_gradients(const Volume& volume, const Positions& world_positions) {
  std::vector<Vec3f> out(world_positions.size(), Vec3f{0, 0, 0});
  if (!volume.grid || world_positions.empty()) return out;
  const openvdb::FloatGrid& grid = *volume.grid;
  const openvdb::math::Transform& xform = grid.transform();
  const openvdb::math::MapBase::ConstPtr map = xform.baseMap();
  const double sign = volume.inside == Inside::Above ? -1.0 : 1.0;
  const bool clamp = volume.dense && !volume.domain.empty();

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, world_positions.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      GradientSampler s{grid.getConstAccessor(), clamp, volume.domain.min(),
                                        volume.domain.max()};
                      for (std::size_t i = r.begin(); i != r.end(); ++i) {
                        const Vec3f& p = world_positions[i];
                        const openvdb::Vec3d q =
                            xform.worldToIndex(openvdb::Vec3d(p[0], p[1], p[2]));
                        const openvdb::Vec3d g = sign * map->applyIJT(s.interpolate(q), q);
                        if (!std::isfinite(g.length())) continue;
                        out[i] = {float(g.x()), float(g.y()), float(g.z())};
                      }
                    });
  return out;
}

double length(const Vec3f& v) {
  return std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
}

Vec3f scaled(const Vec3f& v, double s) {
  return {float(v[0] * s), float(v[1] * s), float(v[2] * s)};
}

}  // namespace

std::vector<Vec3f> gradient_normals(const Volume& volume, const Positions& world_positions) {
  std::vector<Vec3f> normals = outward_gradients(volume, world_positions);
  for (Vec3f& n : normals) {
    const double len = length(n);
    n = len > 0 ? scaled(n, 1.0 / len) : Vec3f{0, 0, 0};
  }
  return normals;
}

MeshNormals gradient_normals_for_mesh(const Volume& volume, const Mesh& mesh) {
  MeshNormals r;
  r.normals = outward_gradients(volume, mesh.positions);
  const std::vector<Vec3f> faces = area_weighted_normals(mesh);
  std::vector<double> lengths(r.normals.size());
  std::vector<double> positive;
  positive.reserve(lengths.size());
  for (std::size_t i = 0; i < lengths.size(); ++i) {
    lengths[i] = length(r.normals[i]);
    if (lengths[i] > 0) positive.push_back(lengths[i]);
  }
  double weak_below = 0;
  if (!positive.empty()) {
    auto mid = positive.begin() + positive.size() / 2;
    std::nth_element(positive.begin(), mid, positive.end());
    weak_below = kWeakGradientFraction * *mid;
  }
  for (std::size_t i = 0; i < r.normals.size(); ++i) {
    Vec3f& n = r.normals[i];
    const Vec3f& a = faces[i];
    const double alen = length(a);
    const bool weak = !(lengths[i] > weak_below);
    const bool opposed =
        !weak && double(n[0]) * a[0] + double(n[1]) * a[1] + double(n[2]) * a[2] <= 0;
    if (alen > 0 && (weak || opposed)) {
      n = scaled(a, 1.0 / alen);
      ++(weak ? r.weak : r.opposed);
    } else {
      n = lengths[i] > 0 ? scaled(n, 1.0 / lengths[i]) : Vec3f{0, 0, 0};
    }
  }
  return r;
}

}  // namespace isocurv::volume
