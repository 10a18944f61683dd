#include "curvature/estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/cl_launch.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"
#include "curvature/vertex_corners.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const curvature_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature {
namespace {

using Clock = std::chrono::steady_clock;

// Milliseconds since `since`, which then moves to now.
double lap(Clock::time_point& since) {
  const Clock::time_point now = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - since).count();
  since = now;
  return ms;
}

// A device buffer kept between calls, reallocated (with 50% headroom) only when too small.
struct Buffer {
  cl::Buffer buffer;
  std::size_t bytes = 0;
  cl::Buffer& reserve(cl::Context& context, std::size_t need) {
    need = std::max<std::size_t>(need, 16);
    if (need > bytes) {
      bytes = std::max(need, bytes + bytes / 2);
      buffer = cl::Buffer(context, CL_MEM_READ_WRITE, bytes);
    }
    return buffer;
  }
};

// What one OpenCL context keeps between calls: kernels, buffers and the adjacency's host storage.
struct Session {
  cl::Context context;  // held, so no later context can reuse its handle
  std::mutex mutex;     // one estimate at a time per context (kernel arguments are shared state)
  cl::Kernel corner_normals_areas, vertex_normals_areas, vertex_boundary, vertex_boundary_large,
      corner_tensors, vertex_sums, vertex_principal, corner_dcurv, vertex_dcurv;
  Buffer positions, triangles, offsets, corners, large_fans, given_normals, corner, sums;
  Buffer normals, area, boundary, k1, k2, dir1, dir2, H, K, shape, curved, ao, dcurv;
  VertexCorners adjacency;
  std::vector<std::uint32_t> large;  // vertices with more than kMaxFan corners
};

// Fans up to this many corners are checked for boundary edges in registers (vertex_boundary).
constexpr std::uint32_t kMaxFan = 8;

const std::string& program_source() {
  static const std::string source =
      std::string(kernels::curvature_math_cl) + "\n" + kernels::curvature_kernels_cl;
  return source;
}

std::string build_options() {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "-DPIVOT_TOLERANCE=%.9g -DOPPOSITE_NORMALS=%.9g -DAO_C0=%.9g -DAO_C1=%.9g "
                "-DAO_C2=%.9g -DAO_SMIN=%.9g -DMAX_FAN=%u",
                kPivotTolerance, kOppositeNormals, kAoC0, kAoC1, kAoC2, kAoSMin, kMaxFan);
  return buf;
}

// The session of `device`'s context, created (program built, kernels made) on first use.
Session& session_for(Device& device) {
  static std::mutex registry_mutex;
  static std::vector<std::unique_ptr<Session>> sessions;
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (auto& s : sessions)
    if (s->context() == device.context()()) return *s;
  auto s = std::make_unique<Session>();
  s->context = device.context();
  cl::Program& program = device.program("curvature", program_source().c_str(), build_options());
  s->corner_normals_areas = cl::Kernel(program, "corner_normals_areas");
  s->vertex_normals_areas = cl::Kernel(program, "vertex_normals_areas");
  s->vertex_boundary = cl::Kernel(program, "vertex_boundary");
  s->vertex_boundary_large = cl::Kernel(program, "vertex_boundary_large");
  s->corner_tensors = cl::Kernel(program, "corner_tensors");
  s->vertex_sums = cl::Kernel(program, "vertex_sums");
  s->vertex_principal = cl::Kernel(program, "vertex_principal");
  s->corner_dcurv = cl::Kernel(program, "corner_dcurv");
  s->vertex_dcurv = cl::Kernel(program, "vertex_dcurv");
  sessions.push_back(std::move(s));
  return *sessions.back();
}

constexpr std::size_t kGroup = 64;  // work-group size of every launch (core/cl_launch.h)

template <class T, class A>
void upload(cl::CommandQueue& q, cl::Context& ctx, Buffer& b, const std::vector<T, A>& v) {
  b.reserve(ctx, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b.buffer, CL_FALSE, 0, v.size() * sizeof(T), v.data());
}

template <class T>
void download(cl::CommandQueue& q, Buffer& b, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  q.enqueueReadBuffer(b.buffer, CL_FALSE, 0, n * sizeof(T), v.data());
}

void run(const Mesh& mesh, Device& device, const Options& options, CurvatureField& out,
         Timings* timings) {
  Clock::time_point clock = Clock::now();
  const Clock::time_point start = clock;
  Timings t;
  check_input(mesh, options);
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  if (nv == 0) {
    out = CurvatureField{};
    if (timings) *timings = t;
    return;
  }
  Session& s = session_for(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  // Separate the steps only when asked to time them.
  auto step = [&](double& ms) {
    if (!timings) return;
    q.finish();
    ms = lap(clock);
  };

  build_vertex_corners(mesh, s.adjacency);
  s.large.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (s.adjacency.offsets[v + 1] - s.adjacency.offsets[v] > kMaxFan)
      s.large.push_back(std::uint32_t(v));
  t.adjacency = lap(clock);

  upload(q, ctx, s.positions, mesh.positions);
  upload(q, ctx, s.triangles, mesh.triangles);
  upload(q, ctx, s.offsets, s.adjacency.offsets);
  upload(q, ctx, s.corners, s.adjacency.corners);
  upload(q, ctx, s.large_fans, s.large);
  const bool given = options.vertex_normals != nullptr;
  if (given)
    upload(q, ctx, s.given_normals, *options.vertex_normals);
  else
    s.given_normals.reserve(ctx, 16);
  s.corner.reserve(ctx, 3 * nf * sizeof(cl_float4));
  s.sums.reserve(ctx, nv * sizeof(cl_float4));
  for (Buffer* b : {&s.area, &s.k1, &s.k2, &s.H, &s.K, &s.shape, &s.curved, &s.ao})
    b->reserve(ctx, nv * sizeof(float));
  for (Buffer* b : {&s.normals, &s.dir1, &s.dir2}) b->reserve(ctx, nv * sizeof(Vec3f));
  s.boundary.reserve(ctx, nv);
  s.dcurv.reserve(ctx, nv * sizeof(cl_float4));
  step(t.upload);

  const cl_uint vcount = cl_uint(nv), fcount = cl_uint(nf), lcount = cl_uint(s.large.size());
  set_args(s.corner_normals_areas, s.positions.buffer, s.triangles.buffer, fcount,
           cl_int(options.normal_weights == NormalWeights::area), s.corner.buffer);
  launch(q, s.corner_normals_areas, nf, kGroup);
  set_args(s.vertex_normals_areas, s.offsets.buffer, s.corners.buffer, s.corner.buffer,
           s.given_normals.buffer, cl_int(given), vcount, s.normals.buffer, s.area.buffer);
  launch(q, s.vertex_normals_areas, nv, kGroup);
  set_args(s.vertex_boundary, s.offsets.buffer, s.corners.buffer, s.triangles.buffer, vcount,
           s.boundary.buffer);
  launch(q, s.vertex_boundary, nv, kGroup);
  set_args(s.vertex_boundary_large, s.offsets.buffer, s.corners.buffer, s.triangles.buffer,
           s.large_fans.buffer, lcount, s.boundary.buffer);
  launch(q, s.vertex_boundary_large, s.large.size(), kGroup);
  step(t.normals_areas);

  set_args(s.corner_tensors, s.positions.buffer, s.triangles.buffer, s.normals.buffer, fcount,
           s.corner.buffer);
  launch(q, s.corner_tensors, nf, kGroup);
  step(t.tensor);

  set_args(s.vertex_sums, s.offsets.buffer, s.corners.buffer, s.corner.buffer, vcount,
           s.sums.buffer);
  launch(q, s.vertex_sums, nv, kGroup);
  set_args(s.vertex_principal, s.sums.buffer, s.normals.buffer, vcount,
           cl_float(options.ao_scale), s.k1.buffer, s.k2.buffer, s.dir1.buffer, s.dir2.buffer,
           s.H.buffer, s.K.buffer, s.shape.buffer, s.curved.buffer, s.ao.buffer);
  launch(q, s.vertex_principal, nv, kGroup);
  step(t.directions);

  set_args(s.corner_dcurv, s.positions.buffer, s.triangles.buffer, s.k1.buffer, s.k2.buffer,
           s.dir1.buffer, s.dir2.buffer, fcount, s.corner.buffer);
  launch(q, s.corner_dcurv, nf, kGroup);
  set_args(s.vertex_dcurv, s.offsets.buffer, s.corners.buffer, s.corner.buffer, s.sums.buffer,
           vcount, s.dcurv.buffer);
  launch(q, s.vertex_dcurv, nv, kGroup);
  step(t.derivative);

  download(q, s.normals, out.normals, nv);
  download(q, s.area, out.area, nv);
  download(q, s.k1, out.k1, nv);
  download(q, s.k2, out.k2, nv);
  download(q, s.dir1, out.dir1, nv);
  download(q, s.dir2, out.dir2, nv);
  download(q, s.H, out.H, nv);
  download(q, s.K, out.K, nv);
  download(q, s.dcurv, out.dcurv, nv);
  download(q, s.shape, out.shape_index, nv);
  download(q, s.curved, out.curvedness, nv);
  download(q, s.ao, out.ao, nv);
  download(q, s.boundary, out.boundary, nv);
  q.finish();
  t.download = lap(clock);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
}

}  // namespace

CurvatureField estimate(const Mesh& mesh, Device& device, const Options& options,
                        Timings* timings) {
  CurvatureField out;
  estimate(mesh, device, options, out, timings);
  return out;
}

void estimate(const Mesh& mesh, Device& device, const Options& options, CurvatureField& out,
              Timings* timings) {
  try {
    run(mesh, device, options, out, timings);
  } catch (const cl::Error& e) {
    try {
      device.queue().finish();  // no copy may still target the field being unwound
    } catch (const cl::Error&) {
    }
    throw Error(std::string("curvature: OpenCL call ") + e.what() + " failed on " +
                device.info().name + ": " + cl_error_name(e.err()));
  }
}

}  // namespace isocurv::curvature
