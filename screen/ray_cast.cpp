#include "screen/ray_cast.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "screen/detail/kernels.h"

namespace isocurv::screen {
namespace {

using V = std::array<double, 3>;

void check(const CastOptions& o) {
  if (!(o.step > 0 && o.step <= 0.5) || o.bisections < 0 || o.bisections > 60)
    throw Error("screen: the ray step must be in (0, 0.5] voxel and bisections in [0, 60]");
}

void frame_depths(GBuffer& g, const volume::DenseField& v) {
  depth_range(g.frame, v.bounds, g.near, g.far);
}

// The reference's march for one ray (index space) through `clip` (the straddling bricks' box,
// DenseField::straddling_box); false when nothing is hit.
bool cast_one(const volume::DenseField& vol, float iso, const std::array<int, 6>& clip, const V& oi,
              const V& di, const CastOptions& opt, V& hit) {
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double lo = clip[2 * a], hi = clip[2 * a + 1];
    if (di[a] == 0) {
      if (oi[a] < lo || oi[a] > hi) return false;
    } else {
      double ta = (lo - oi[a]) / di[a], tb = (hi - oi[a]) / di[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta), t1 = std::min(t1, tb);
    }
  }
  if (!(t1 > t0)) return false;
  const V base = {oi[0] + t0 * di[0], oi[1] + t0 * di[1], oi[2] + t0 * di[2]};
  auto at = [&](double t) {
    return V{base[0] + t * di[0], base[1] + t * di[1], base[2] + t * di[2]};
  };
  const double tl = t1 - t0;
  const double dmax = std::max({std::abs(di[0]), std::abs(di[1]), std::abs(di[2])});
  const double dt = opt.step / dmax;
  const double l1 = std::abs(di[0]) + std::abs(di[1]) + std::abs(di[2]);
  const int nb[3] = {vol.bx, vol.by, vol.bz};
  double t = 0, s_prev = vol.field(base, iso), a = 0, b = 0, fa = 0, fb = 0;
  bool known = true;  // s_prev is the field at t (false after a jump over a brick)
  bool found = false;
  while (t < tl) {
    const V p = at(t);
    int bc[3];
    for (int k = 0; k < 3; ++k)
      bc[k] = std::min(std::max(int(std::floor(p[k] / volume::kFieldBrick)), 0), nb[k] - 1);
    const std::size_t bi =
        std::size_t(bc[0]) + std::size_t(vol.bx) * (bc[1] + std::size_t(vol.by) * bc[2]);
    double te = std::numeric_limits<double>::infinity();  // where the ray leaves the brick
    for (int k = 0; k < 3; ++k) {
      if (di[k] == 0) continue;
      const double ex = (di[k] > 0 ? bc[k] + 1 : bc[k]) * double(volume::kFieldBrick);
      te = std::min(te, (ex - base[k]) / di[k]);
    }
    double tn = t + dt;
    if (!vol.brick_straddles(bi, iso)) {  // no crossing inside: on to its exit, unsampled
      t = std::min(std::max(tn, te), tl);
      known = false;
      continue;
    }
    if (!known) s_prev = vol.field(p, iso), known = true;
    if (opt.safe_stride && s_prev < 0) {
      const double slope = vol.brick_slope[bi];
      const double ts =
          slope > 0 ? 0.9 * -s_prev / (slope * l1) : std::numeric_limits<double>::infinity();
      if (ts > dt) tn = std::max(tn, std::min(t + ts, te));
    }
    tn = std::min(tn, tl);
    const double s = vol.field(at(tn), iso);
    if (s_prev <= 0 && s > 0) {
      found = true, a = t, b = tn, fa = s_prev, fb = s;
      break;
    }
    s_prev = s;
    t = tn;
  }
  if (!found) return false;
  for (int i = 0; i < opt.bisections; ++i) {
    const double m = 0.5 * (a + b), fm = vol.field(at(m), iso);
    if (fm > 0)
      b = m, fb = fm;
    else
      a = m, fa = fm;
  }
  // Secant between the ends (fa <= 0 < fb), kept inside the bracket.
  const double tm = opt.secant ? std::clamp(a + (b - a) * fa / (fa - fb), a, b) : 0.5 * (a + b);
  hit = at(tm);
  return true;
}

struct CastState {
  explicit CastState(Device&) {}
  std::mutex mutex;
  std::uint64_t uploaded = 0;  // volume::DenseField::id of the volume on the device
  cl::Buffer values, bricks, slopes, xform, cam, position, normal, depth;
  std::size_t pixels = 0;
  std::vector<cl_float4> host_pos, host_nrm;
};

}  // namespace

GBuffer ray_cast_reference(const volume::DenseField& vol, float iso, const ViewFrame& frame,
                           const CastOptions& opt) {
  check(opt);
  GBuffer g;
  g.reset(frame);
  frame_depths(g, vol);
  std::array<int, 6> clip{};
  if (!vol.straddling_box(iso, clip)) return g;  // no surface at this isovalue
  tbb::parallel_for(tbb::blocked_range<int>(0, frame.height),
                    [&](const tbb::blocked_range<int>& r) {
                      for (int y = r.begin(); y != r.end(); ++y)
                        for (int x = 0; x < frame.width; ++x) {
                          V o, d;
                          frame.ray(x + 0.5, y + 0.5, o, d);
                          const V oi = vol.index(o);
                          V di;
                          for (int k = 0; k < 3; ++k)
                            di[k] = vol.to_index[4 * k] * d[0] + vol.to_index[4 * k + 1] * d[1] +
                                    vol.to_index[4 * k + 2] * d[2];
                          V q;
                          if (!cast_one(vol, iso, clip, oi, di, opt, q)) continue;
                          const V n = vol.normal(q);
                          if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
                          const V p = vol.world(q);
                          const std::size_t i = std::size_t(x) + std::size_t(frame.width) * y;
                          g.position[i] = {float(p[0]), float(p[1]), float(p[2])};
                          g.normal[i] = {float(n[0]), float(n[1]), float(n[2])};
                          g.depth[i] = float(frame.eye_depth(p));
                          g.valid[i] = 1;
                        }
                    });
  return g;
}

GBuffer ray_cast(const volume::DenseField& vol, float iso, const ViewFrame& frame, Device& device,
                 const CastOptions& opt, int work_group) {
  check(opt);
  if (work_group < 1) throw Error("screen: the work-group size must be positive");
  GBuffer g;
  g.reset(frame);
  frame_depths(g, vol);
  std::array<int, 6> clip{};
  if (!vol.straddling_box(iso, clip)) return g;  // no surface at this isovalue
  float cam[16] = {0};  // outside device_call: copied from until the queue drains
  device_call(device, "screen", [&] {
  CastState& s = device.state<CastState>();
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  if (s.uploaded != vol.id) {
    s.values = cl::Buffer(ctx, CL_MEM_READ_ONLY, std::max<std::size_t>(4, vol.values.size() * 4));
    q.enqueueWriteBuffer(s.values, CL_FALSE, 0, vol.values.size() * 4, vol.values.data());
    s.bricks =
        cl::Buffer(ctx, CL_MEM_READ_ONLY, std::max<std::size_t>(8, vol.brick_range.size() * 8));
    q.enqueueWriteBuffer(s.bricks, CL_FALSE, 0, vol.brick_range.size() * 8, vol.brick_range.data());
    s.slopes =
        cl::Buffer(ctx, CL_MEM_READ_ONLY, std::max<std::size_t>(4, vol.brick_slope.size() * 4));
    q.enqueueWriteBuffer(s.slopes, CL_FALSE, 0, vol.brick_slope.size() * 4, vol.brick_slope.data());
    const std::array<float, 36> xf = vol.device_transform();
    s.xform = cl::Buffer(ctx, CL_MEM_READ_ONLY, xf.size() * 4);
    q.enqueueWriteBuffer(s.xform, CL_TRUE, 0, xf.size() * 4, xf.data());
    s.uploaded = vol.id;
  }
  const std::size_t n = g.pixels();
  if (n > s.pixels) {
    s.position = cl::Buffer(ctx, CL_MEM_WRITE_ONLY, n * 16);
    s.normal = cl::Buffer(ctx, CL_MEM_WRITE_ONLY, n * 16);
    s.depth = cl::Buffer(ctx, CL_MEM_WRITE_ONLY, n * 4);
    s.pixels = n;
  }
  if (!s.cam()) s.cam = cl::Buffer(ctx, CL_MEM_READ_ONLY, 16 * 4);
  for (int c = 0; c < 3; ++c) {
    cam[c] = float(frame.eye[c]), cam[3 + c] = float(frame.forward[c]);
    cam[6 + c] = float(frame.right[c]), cam[9 + c] = float(frame.up[c]);
  }
  cam[12] = float(frame.half_height), cam[13] = frame.ortho ? 1.0f : 0.0f;
  q.enqueueWriteBuffer(s.cam, CL_FALSE, 0, sizeof cam, cam);
  cl::Kernel& k = device.kernel(detail::screen_program(device), "ray_cast");
  set_args(k, s.values, s.bricks, s.slopes, cl_int4{{vol.nx, vol.ny, vol.nz, vol.sparse ? 1 : 0}},
           cl_int4{{vol.bx, vol.by, vol.bz, 0}},
           cl_float4{{float(clip[0]), float(clip[2]), float(clip[4]), 0.f}},
           cl_float4{{float(clip[1]), float(clip[3]), float(clip[5]), 0.f}}, cl_float(iso),
           cl_float(vol.sign), s.xform, s.cam, cl_int(frame.width), cl_int(frame.height),
           cl_float(opt.step), cl_int(opt.bisections), cl_int(opt.safe_stride ? 1 : 0),
           cl_int(opt.secant ? 1 : 0), s.position, s.normal, s.depth);
  launch(q, k, n, std::size_t(work_group));
  s.host_pos.resize(n), s.host_nrm.resize(n);
  q.enqueueReadBuffer(s.position, CL_FALSE, 0, n * 16, s.host_pos.data());
  q.enqueueReadBuffer(s.normal, CL_FALSE, 0, n * 16, s.host_nrm.data());
  q.enqueueReadBuffer(s.depth, CL_TRUE, 0, n * 4, g.depth.data());
  for (std::size_t i = 0; i < n; ++i) {
    const cl_float4& p = s.host_pos[i];
    const cl_float4& m = s.host_nrm[i];
    g.position[i] = {p.s[0], p.s[1], p.s[2]};
    g.normal[i] = {m.s[0], m.s[1], m.s[2]};
    g.valid[i] = p.s[3] != 0.0f;
  }
  });
  return g;
}

}  // namespace isocurv::screen
