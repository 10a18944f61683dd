#include "screen/rasterise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/vec3.h"

namespace isocurv::screen {
namespace {

using V = std::array<double, 3>;
using vec3::sub;
using vec3::dot;
using vec3::cross;
using vec3::to_double;

constexpr int kBand = 16;  // image rows per parallel task

}  // namespace

GBuffer rasterise(const Mesh& mesh, const std::vector<Vec3f>& normals, const ViewFrame& frame,
                  RasterHits* hits) {
  const std::size_t nv = mesh.positions.size();
  if (normals.size() != nv) throw Error("screen: the mesh needs one normal per vertex");
  for (const Tri& t : mesh.triangles)
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw Error("screen: a triangle index is out of range");
  GBuffer g;
  g.reset(frame);
  if (hits) {
    hits->triangle.assign(g.pixels(), RasterHits::kNone);
    hits->uv.assign(g.pixels(), {0.f, 0.f});
  }
  std::array<double, 6> b = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (const Vec3f& p : mesh.positions)
    for (int c = 0; c < 3; ++c)
      b[2 * c] = std::min(b[2 * c], double(p[c])),
            b[2 * c + 1] = std::max(b[2 * c + 1], double(p[c]));
  if (nv == 0) b = {0, 1, 0, 1, 0, 1};
  depth_range(frame, b, g.near, g.far);
  // Each triangle's pixel box (inclusive), once; empty when it is clipped or off screen.
  struct Box {
    int x0, x1, y0, y1;
  };
  std::vector<Box> boxes(mesh.triangles.size());
  tbb::parallel_for(std::size_t(0), mesh.triangles.size(), [&](std::size_t f) {
    const Tri& t = mesh.triangles[f];
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    bool ok = true;
    for (int j = 0; j < 3; ++j) {
      double x, y, z;
      if (!frame.project(to_double(mesh.positions[t[j]]), x, y, z) || (!frame.ortho && z < g.near))
        ok = false;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    Box& bx = boxes[f];
    bx = {1, 0, 1, 0};
    if (!ok) return;
    // Pixel centres x + 0.5 in [x0, x1].
    bx.x0 = std::max(0, int(std::ceil(x0 - 0.5))),
    bx.x1 = std::min(frame.width - 1, int(std::floor(x1 - 0.5)));
    bx.y0 = std::max(0, int(std::ceil(y0 - 0.5))),
    bx.y1 = std::min(frame.height - 1, int(std::floor(y1 - 0.5)));
  });
  const int bands = (frame.height + kBand - 1) / kBand;
  tbb::parallel_for(0, bands, [&](int band) {
    const int ya = band * kBand, yb = std::min(frame.height, ya + kBand) - 1;
    std::vector<double> zbuf(std::size_t(frame.width) * (yb - ya + 1),
                             std::numeric_limits<double>::infinity());
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const Box& bx = boxes[f];
      const int y0 = std::max(bx.y0, ya), y1 = std::min(bx.y1, yb);
      if (bx.x0 > bx.x1 || y0 > y1) continue;
      const Tri& t = mesh.triangles[f];
      const V p0 = to_double(mesh.positions[t[0]]), e1 = sub(to_double(mesh.positions[t[1]]), p0),
              e2 = sub(to_double(mesh.positions[t[2]]), p0);
      for (int y = y0; y <= y1; ++y)
        for (int x = bx.x0; x <= bx.x1; ++x) {
          V o, d;
          frame.ray(x + 0.5, y + 0.5, o, d);
          // Moller-Trumbore.
          const V pv = cross(d, e2);
          const double det = dot(e1, pv);
          if (det == 0) continue;
          const V tv = sub(o, p0);
          const double u = dot(tv, pv) / det;
          if (u < 0 || u > 1) continue;
          const V qv = cross(tv, e1);
          const double v = dot(d, qv) / det;
          if (v < 0 || u + v > 1) continue;
          const double s = dot(e2, qv) / det;
          const V p = {o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]};
          const double z = frame.eye_depth(p);
          if (!(s > 0) || (!frame.ortho && z < g.near)) continue;
          double& zb = zbuf[std::size_t(x) + std::size_t(frame.width) * (y - ya)];
          if (!(z < zb)) continue;
          zb = z;
          const std::size_t i = std::size_t(x) + std::size_t(frame.width) * y;
          V n;
          const double w0 = 1 - u - v;
          for (int c = 0; c < 3; ++c)
            n[c] = w0 * normals[t[0]][c] + u * normals[t[1]][c] + v * normals[t[2]][c];
          const double len = std::sqrt(dot(n, n));
          g.position[i] = {float(p[0]), float(p[1]), float(p[2])};
          g.depth[i] = float(z);
          if (hits) {
            hits->triangle[i] = static_cast<std::uint32_t>(f);
            hits->uv[i] = {float(u), float(v)};
          }
          if (len > 0) {
            g.normal[i] = {float(n[0] / len), float(n[1] / len), float(n[2] / len)};
            g.valid[i] = 1;
          } else {
            g.normal[i] = {0, 0, 0};
            g.valid[i] = 0;
          }
        }
    }
  });
  return g;
}

std::vector<float> interpolate(const Mesh& mesh, const RasterHits& hits,
                               const std::vector<float>& values) {
  if (values.size() != mesh.positions.size())
    throw Error("screen: interpolate needs one value per vertex");
  std::vector<float> out(hits.triangle.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::uint32_t f = hits.triangle[i];
    if (f == RasterHits::kNone) continue;
    if (f >= mesh.triangles.size()) throw Error("screen: a hit names a triangle the mesh lacks");
    const Tri& t = mesh.triangles[f];
    const double u = hits.uv[i][0], v = hits.uv[i][1];
    out[i] = float((1 - u - v) * values[t[0]] + u * values[t[1]] + v * values[t[2]]);
  }
  return out;
}

}  // namespace isocurv::screen
