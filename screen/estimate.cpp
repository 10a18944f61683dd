#include "screen/estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "core/vec3.h"
#include "curvature/prantl.h"
#include "screen/detail/kernels.h"

namespace isocurv::screen {
namespace {

constexpr int kDX[8] = {1, 1, 0, -1, -1, -1, 0, 1};
constexpr int kDY[8] = {0, 1, 1, 1, 0, -1, -1, -1};

void check(const GBuffer& g, const ScreenOptions& o) {
  const std::size_t n = g.pixels();
  if (g.position.size() != n || g.normal.size() != n || g.depth.size() != n || g.valid.size() != n)
    throw Error("screen: the G-buffer's arrays do not match its size");
  if (o.edges != 2 && o.edges != 3) throw Error("screen: --edges takes 2 or 3");
  if (o.fan != 4 && o.fan != 8) throw Error("screen: the LOD fan takes 4 or 8 triangles");
  if (o.size_max < 1 || o.size_max > 64) throw Error("screen: the LOD size must be in [1, 64]");
  if (o.mellado_radius < 1 || o.mellado_radius > 32)
    throw Error("screen: the Mellado radius must be in [1, 32] pixels");
  if (!(g.near > 0 || g.frame.ortho) || !(g.far > g.near))
    throw Error("screen: the G-buffer's depth range is empty");
}

// Everything the per-pixel rules read, as the kernel's Params has it.
struct Rules {
  int width, height;
  double near, far, f_lod, tau;
  bool ortho, linear;
  double window(double z) const {
    double d;
    if (linear)
      d = z / far;
    else if (ortho)
      d = (z - near) / (far - near);
    else
      d = (1 / near - 1 / z) / (1 / near - 1 / far);
    return std::min(std::max(d, 0.0), 1.0);
  }
};

Rules rules_for(const GBuffer& g, const ScreenOptions& o) {
  const double f = lod_far(g);
  return {g.width(), g.height(), g.near,        g.far,
          f,         1 / f,      g.frame.ortho, o.depth == DepthMapping::linear};
}

using A3 = std::array<double, 3>;
using vec3::to_double;
using vec3::dot;

struct Pixel {
  const GBuffer& g;
  const ScreenOptions& o;
  const Rules& r;
  int x, y, c;
  double dc;

  float depth_of(int q) const { return float(r.window(double(g.depth[q]))); }
  int neighbour(int k, int step) const {
    const int qx = x + step * kDX[k], qy = y + step * kDY[k];
    if (qx < 0 || qy < 0 || qx >= r.width || qy >= r.height) return -1;
    const int q = qx + r.width * qy;
    if (!g.valid[q]) return -1;
    if (std::abs(r.window(g.depth[q]) - dc) > r.tau) return -1;
    return q;
  }
  bool triangle(int a, int b, double& h, double& k) const {
    if (a < 0 || b < 0) return false;
    const A3 n0 = to_double(g.normal[c]), n1 = to_double(g.normal[a]), n2 = to_double(g.normal[b]);
    if (o.max_normal_angle_deg > 0) {
      const double cmax = std::cos(o.max_normal_angle_deg * M_PI / 180);
      if (dot(n0, n1) < cmax || dot(n1, n2) < cmax || dot(n2, n0) < cmax) return false;
    }
    std::array<A3, 3> p, n = {n0, n1, n2};
    const int idx[3] = {c, a, b};
    for (int j = 0; j < 3; ++j)
      for (int m = 0; m < 3; ++m) p[j][m] = double(g.position[idx[j]][m]) - g.position[c][m];
    curvature::TriangleShape s;
    if (!curvature::prantl_triangle(p, n, o.edges, s)) return false;
    h = s.H(), k = s.K();
    return true;
  }
};

void prantl_pixel(const Pixel& px, ScreenCurvature& out) {
  const ScreenOptions& o = px.o;
  const int s = o.lod ? int(std::floor(o.size_max * std::pow(px.r.f_lod, -2.0 * px.dc))) + 1 : 1;
  double sh = 0, sk = 0;
  int count = 0;
  if (s > 1) {
    int nb[8];
    for (int k = 0; k < 8; ++k) {
      nb[k] = -1;
      if (o.fan == 4 && (k & 1)) continue;
      nb[k] = px.neighbour(k, s);
      if (nb[k] < 0 && o.rule == DiscontinuityRule::report) nb[k] = px.neighbour(k, 1);
    }
    const int inc = o.fan == 4 ? 2 : 1;
    for (int k = 0; k < 8; k += inc) {
      double h, kk;
      if (px.triangle(nb[k], nb[(k + inc) & 7], h, kk)) sh += h, sk += kk, ++count;
    }
  }
  int used = s;
  if (count == 0) {
    used = 1;
    for (int k = 0; k < 8 && count == 0; k += 2) {
      double h, kk;
      if (px.triangle(px.neighbour(k, 1), px.neighbour((k + 2) & 7, 1), h, kk))
        sh = h, sk = kk, count = 1;
    }
  }
  if (count == 0) return;
  out.H[px.c] = float(sh / count), out.K[px.c] = float(sk / count);
  out.valid[px.c] = 1, out.step[px.c] = std::uint8_t(used);
}

void mellado_pixel(const Pixel& px, ScreenCurvature& out) {
  const GBuffer& g = px.g;
  const int r = px.o.mellado_radius;
  const A3 pc = to_double(g.position[px.c]);
  auto visit = [&](auto&& f) {
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i) {
        const int qx = px.x + i, qy = px.y + j;
        if (i * i + j * j > r * r || qx < 0 || qy < 0 || qx >= px.r.width || qy >= px.r.height)
          continue;
        const int q = qx + px.r.width * qy;
        if (!g.valid[q] || std::abs(px.r.window(g.depth[q]) - px.dc) > px.r.tau) continue;
        const A3 p = to_double(g.position[q]);
        f(A3{p[0] - pc[0], p[1] - pc[1], p[2] - pc[2]}, to_double(g.normal[q]));
      }
  };
  double h2 = 0;
  int count = 0;
  visit([&](const A3& d, const A3&) { h2 = std::max(h2, dot(d, d)), ++count; });
  if (count < 6 || !(h2 > 0)) return;
  h2 *= 2.25;
  // The weighted means, then the sums about them (as the kernel, where float needs it).
  double sw = 0;
  A3 sx{0, 0, 0}, sn{0, 0, 0};
  auto weight = [&](const A3& d) {
    const double u = 1 - dot(d, d) / h2;
    return u * u * u * u;
  };
  visit([&](const A3& d, const A3& n) {
    const double w = weight(d);
    sw += w;
    for (int m = 0; m < 3; ++m) sx[m] += w * d[m], sn[m] += w * n[m];
  });
  const A3 mx = {sx[0] / sw, sx[1] / sw, sx[2] / sw}, mn = {sn[0] / sw, sn[1] / sw, sn[2] / sw};
  double cxx = 0, cxn = 0;
  visit([&](const A3& d, const A3& n) {
    const double w = weight(d);
    const A3 dx = {d[0] - mx[0], d[1] - mx[1], d[2] - mx[2]};
    const A3 dn = {n[0] - mn[0], n[1] - mn[1], n[2] - mn[2]};
    cxx += w * dot(dx, dx), cxn += w * dot(dx, dn);
  });
  if (!(cxx > 0)) return;
  const double uq = 0.5 * cxn / cxx;
  A3 ul;
  for (int m = 0; m < 3; ++m) ul[m] = mn[m] - 2 * uq * mx[m];
  const double len = std::sqrt(dot(ul, ul));
  if (!(len > 0)) return;
  out.H[px.c] = float(2 * uq / len), out.K[px.c] = 0;
  out.valid[px.c] = 1, out.step[px.c] = std::uint8_t(r);
}

ScreenCurvature empty_result(const GBuffer& g) {
  ScreenCurvature out;
  out.width = g.width(), out.height = g.height();
  out.H.assign(g.pixels(), 0.0f), out.K.assign(g.pixels(), 0.0f);
  out.valid.assign(g.pixels(), 0), out.step.assign(g.pixels(), 0);
  return out;
}

// The kernel's Params (screen_kernels.cl), field for field.
struct Params {
  cl_int width, height, edges, lod, size_max, fan, paper_rule, mellado_radius;
  cl_float near, far, f_lod, tau, cos_max;
  cl_int ortho, linear_depth;
};

struct EstimateState {
  explicit EstimateState(Device&) {}
  std::mutex mutex;
  cl::Buffer pos, nrm, depth, out;
  std::size_t pixels = 0;
  std::vector<cl_float4> host_pos, host_nrm, host_out;
};

}  // namespace

std::size_t ScreenCurvature::valid_count() const {
  return std::size_t(std::count(valid.begin(), valid.end(), std::uint8_t(1)));
}

std::string estimator_label(const ScreenOptions& so, double smoothing_voxels) {
  std::string label =
      so.estimator == ScreenEstimator::mellado
          ? "screen-space Mellado, radius " + std::to_string(so.mellado_radius) + " px"
          : "screen-space Prantl, " + std::to_string(so.edges) + " edges" + (so.lod ? ", LOD" : "");
  if (smoothing_voxels > 0) {
    char text[48];
    std::snprintf(text, sizeof text, ", smoothed %g voxel%s", smoothing_voxels,
                  smoothing_voxels == 1 ? "" : "s");
    label += text;
  }
  return label;
}

double lod_far(const GBuffer& g) { return std::max(g.far, 100.0); }

ScreenCurvature estimate_reference(const GBuffer& g, const ScreenOptions& o) {
  check(g, o);
  ScreenCurvature out = empty_result(g);
  const Rules r = rules_for(g, o);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.height()),
                    [&](const tbb::blocked_range<int>& rows) {
                      for (int y = rows.begin(); y != rows.end(); ++y)
                        for (int x = 0; x < g.width(); ++x) {
                          const int c = x + g.width() * y;
                          if (!g.valid[c]) continue;
                          const Pixel px{g, o, r, x, y, c, r.window(g.depth[c])};
                          if (o.estimator == ScreenEstimator::prantl)
                            prantl_pixel(px, out);
                          else
                            mellado_pixel(px, out);
                        }
                    });
  return out;
}

ScreenCurvature estimate(const GBuffer& g, Device& device, const ScreenOptions& o, int work_group) {
  check(g, o);
  if (work_group < 1) throw Error("screen: the work-group size must be positive");
  ScreenCurvature out = empty_result(g);
  const std::size_t n = g.pixels();
  return device_call(device, "screen", [&] {
  EstimateState& s = device.state<EstimateState>();
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  if (n > s.pixels) {
    s.pos = cl::Buffer(ctx, CL_MEM_READ_ONLY, n * 16);
    s.nrm = cl::Buffer(ctx, CL_MEM_READ_ONLY, n * 16);
    s.depth = cl::Buffer(ctx, CL_MEM_READ_ONLY, n * 4);
    s.out = cl::Buffer(ctx, CL_MEM_WRITE_ONLY, n * 16);
    s.pixels = n;
  }
  s.host_pos.resize(n), s.host_nrm.resize(n), s.host_out.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.host_pos[i] = {
        {g.position[i][0], g.position[i][1], g.position[i][2], g.valid[i] ? 1.0f : 0.0f}};
    s.host_nrm[i] = {{g.normal[i][0], g.normal[i][1], g.normal[i][2], 0.0f}};
  }
  q.enqueueWriteBuffer(s.pos, CL_FALSE, 0, n * 16, s.host_pos.data());
  q.enqueueWriteBuffer(s.nrm, CL_FALSE, 0, n * 16, s.host_nrm.data());
  q.enqueueWriteBuffer(s.depth, CL_FALSE, 0, n * 4, g.depth.data());
  const Rules r = rules_for(g, o);
  const Params p{
      g.width(),
      g.height(),
      o.edges,
      o.lod ? 1 : 0,
      o.size_max,
      o.fan,
      o.rule == DiscontinuityRule::paper ? 1 : 0,
      o.mellado_radius,
      float(r.near),
      float(r.far),
      float(r.f_lod),
      float(r.tau),
      o.max_normal_angle_deg > 0 ? float(std::cos(o.max_normal_angle_deg * M_PI / 180)) : -2.0f,
      r.ortho ? 1 : 0,
      r.linear ? 1 : 0};
  cl::Kernel& k =
      device.kernel(detail::screen_program(device),
                    o.estimator == ScreenEstimator::prantl ? "screen_prantl" : "screen_mellado");
  set_args(k, s.pos, s.nrm, s.depth, p, s.out);
  launch(q, k, n, std::size_t(work_group));
  q.enqueueReadBuffer(s.out, CL_TRUE, 0, n * 16, s.host_out.data());
  for (std::size_t i = 0; i < n; ++i) {
    const cl_float4& v = s.host_out[i];
    if (v.s[2] == 0.0f) continue;
    out.H[i] = v.s[0], out.K[i] = v.s[1], out.valid[i] = 1, out.step[i] = std::uint8_t(v.s[3]);
  }
  return out;
  });
}

}  // namespace isocurv::screen
