#include "curvature/estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/cl_launch.h"
#include "core/cl_scratch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "curvature/derived.h"
#include "curvature/detail/math_options.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"
#include "curvature/topology.h"
#include "curvature/vertex_corners.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const curvature_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature {
namespace {

using Clock = StepClock;

// The device buffers of one estimate, kept between calls in the session's ScratchBuffers.
enum Slot : std::size_t {
  kPositions, kTriangles, kOffsets, kCorners, kLargeFans, kGivenNormals, kCorner, kSums,
  kNormals, kArea, kBoundary, kK1, kK2, kDir1, kDir2, kH, kK, kShape, kCurved, kAo, kDcurv,
  kSlots
};

const std::string& program_source() {
  static const std::string source =
      std::string(kernels::curvature_math_cl) + "\n" + kernels::curvature_kernels_cl;
  return source;
}

std::string build_options() {
  return detail::math_build_options() + " -DMAX_FAN=" + std::to_string(kMaxFan);
}

// What the estimator keeps on one device between calls (Device::state): kernels, buffers and
// the adjacency's host storage.
struct Session {
  explicit Session(Device& device) : buffers(device, kSlots) {
    cl::Program& program = device.program("curvature", program_source().c_str(), build_options());
    corner_normals_areas = cl::Kernel(program, "corner_normals_areas");
    vertex_normals_areas = cl::Kernel(program, "vertex_normals_areas");
    vertex_boundary = cl::Kernel(program, "vertex_boundary");
    vertex_boundary_large = cl::Kernel(program, "vertex_boundary_large");
    corner_tensors = cl::Kernel(program, "corner_tensors");
    vertex_sums = cl::Kernel(program, "vertex_sums");
    vertex_principal = cl::Kernel(program, "vertex_principal");
    corner_dcurv = cl::Kernel(program, "corner_dcurv");
    vertex_dcurv = cl::Kernel(program, "vertex_dcurv");
  }
  std::mutex mutex;  // one estimate at a time per device (kernel arguments are shared state)
  ScratchBuffers buffers;
  cl::Kernel corner_normals_areas, vertex_normals_areas, vertex_boundary, vertex_boundary_large,
      corner_tensors, vertex_sums, vertex_principal, corner_dcurv, vertex_dcurv;
  VertexCorners adjacency;
  std::vector<std::uint32_t> large;  // vertices with more than kMaxFan corners

  cl::Buffer& operator[](Slot slot) { return buffers.get(slot, 16); }
  cl::Buffer& reserve(Slot slot, std::size_t bytes) {
    return buffers.get(slot, std::max<std::size_t>(bytes, 16));
  }
};

// The session of `device`, created (program built, kernels made) on first use.
Session& session_for(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<Session>();
}

constexpr std::size_t kGroup = 64;  // work-group size of every launch (core/cl_launch.h)

template <class T, class A>
void upload(cl::CommandQueue& q, Session& s, Slot slot, const std::vector<T, A>& v) {
  cl::Buffer& b = s.reserve(slot, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b, CL_FALSE, 0, v.size() * sizeof(T), v.data());
}

template <class T>
void download(cl::CommandQueue& q, Session& s, Slot slot, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  q.enqueueReadBuffer(s[slot], CL_FALSE, 0, n * sizeof(T), v.data());
}

// The device arrays one estimate reads: the cold path's session slots or a prepared Topology's.
struct MeshBuffers {
  const cl::Buffer &positions, &triangles, &offsets, &corners, &large;
  std::size_t nv, nf, large_count;
};

// Uploads the given normals and reserves every per-frame buffer, runs every pass and downloads
// into `out`. Call with s.mutex held; nv > 0. `clock` and `t` as in run(). Both the cold and the
// prepared paths come through here, which is what makes them bit-identical.
void passes(Session& s, Device& device, const MeshBuffers& m, const Options& options,
            CurvatureField& out, bool timed, Clock::time_point& clock, Timings& t) {
  cl::CommandQueue& q = device.queue();
  auto step = [&](double& ms) {
    if (!timed) return;
    q.finish();
    ms = lap(clock);
  };
  const std::size_t nv = m.nv, nf = m.nf;
  const bool given = options.vertex_normals != nullptr;
  if (given)
    upload(q, s, kGivenNormals, *options.vertex_normals);
  else
    s.reserve(kGivenNormals, 16);
  s.reserve(kCorner, 3 * nf * sizeof(cl_float4));
  s.reserve(kSums, nv * sizeof(cl_float4));
  for (Slot b : {kArea, kK1, kK2, kH, kK, kShape, kCurved, kAo}) s.reserve(b, nv * sizeof(float));
  for (Slot b : {kNormals, kDir1, kDir2}) s.reserve(b, nv * sizeof(Vec3f));
  s.reserve(kBoundary, nv);
  s.reserve(kDcurv, nv * sizeof(cl_float4));
  step(t.upload);

  const cl_uint vcount = cl_uint(nv), fcount = cl_uint(nf), lcount = cl_uint(m.large_count);
  set_args(s.corner_normals_areas, m.positions, m.triangles, fcount,
           cl_int(options.normal_weights == NormalWeights::area), s[kCorner]);
  launch(q, s.corner_normals_areas, nf, kGroup);
  set_args(s.vertex_normals_areas, m.offsets, m.corners, s[kCorner],
           s[kGivenNormals], cl_int(given), vcount, s[kNormals], s[kArea]);
  launch(q, s.vertex_normals_areas, nv, kGroup);
  set_args(s.vertex_boundary, m.offsets, m.corners, m.triangles, vcount, s[kBoundary]);
  launch(q, s.vertex_boundary, nv, kGroup);
  set_args(s.vertex_boundary_large, m.offsets, m.corners, m.triangles, m.large, lcount,
           s[kBoundary]);
  launch(q, s.vertex_boundary_large, m.large_count, kGroup);
  step(t.normals_areas);

  set_args(s.corner_tensors, m.positions, m.triangles, s[kNormals], fcount, s[kCorner]);
  launch(q, s.corner_tensors, nf, kGroup);
  step(t.tensor);

  set_args(s.vertex_sums, m.offsets, m.corners, s[kCorner], vcount, s[kSums]);
  launch(q, s.vertex_sums, nv, kGroup);
  set_args(s.vertex_principal, s[kSums], s[kNormals], vcount,
           cl_float(options.ao_scale), s[kK1], s[kK2], s[kDir1], s[kDir2],
           s[kH], s[kK], s[kShape], s[kCurved], s[kAo]);
  launch(q, s.vertex_principal, nv, kGroup);
  step(t.directions);

  set_args(s.corner_dcurv, m.positions, m.triangles, s[kK1], s[kK2], s[kDir1], s[kDir2],
           fcount, s[kCorner]);
  launch(q, s.corner_dcurv, nf, kGroup);
  set_args(s.vertex_dcurv, m.offsets, m.corners, s[kCorner], s[kSums], vcount, s[kDcurv]);
  launch(q, s.vertex_dcurv, nv, kGroup);
  step(t.derivative);

  download(q, s, kNormals, out.normals, nv);
  download(q, s, kArea, out.area, nv);
  download(q, s, kK1, out.k1, nv);
  download(q, s, kK2, out.k2, nv);
  download(q, s, kDir1, out.dir1, nv);
  download(q, s, kDir2, out.dir2, nv);
  download(q, s, kH, out.H, nv);
  download(q, s, kK, out.K, nv);
  download(q, s, kDcurv, out.dcurv, nv);
  download(q, s, kShape, out.shape_index, nv);
  download(q, s, kCurved, out.curvedness, nv);
  download(q, s, kAo, out.ao, nv);
  download(q, s, kBoundary, out.boundary, nv);
  q.finish();
  t.download = lap(clock);
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
  cl::CommandQueue& q = device.queue();

  build_vertex_corners(mesh, s.adjacency);
  s.large.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (s.adjacency.offsets[v + 1] - s.adjacency.offsets[v] > kMaxFan)
      s.large.push_back(std::uint32_t(v));
  t.adjacency = lap(clock);

  upload(q, s, kPositions, mesh.positions);
  upload(q, s, kTriangles, mesh.triangles);
  upload(q, s, kOffsets, s.adjacency.offsets);
  upload(q, s, kCorners, s.adjacency.corners);
  upload(q, s, kLargeFans, s.large);
  const MeshBuffers m{s[kPositions], s[kTriangles], s[kOffsets], s[kCorners], s[kLargeFans],
                      nv, nf, s.large.size()};
  passes(s, device, m, options, out, timings != nullptr, clock, t);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
}

// The prepared path: topo's buffers, positions already on the device.
void run_resident(Topology& topo, Device& device, const Options& options, CurvatureField& out,
                  Timings* timings, Clock::time_point start, double upload_ms) {
  Clock::time_point clock = Clock::now();
  Timings t;
  const std::size_t nv = topo.vertex_count();
  if (nv == 0) {
    out = CurvatureField{};
    if (timings) *timings = t;
    return;
  }
  Session& s = session_for(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  const MeshBuffers m{topo.positions(), topo.triangle_buffer(), topo.offsets_buffer(),
                      topo.corners_buffer(), topo.large_fans_buffer(), nv,
                      topo.triangle_count(), topo.large_fan_count()};
  passes(s, device, m, options, out, timings != nullptr, clock, t);
  t.upload += upload_ms;  // positions (estimate) plus given normals (passes)
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
}

void check_prepared(const Topology& topo, Device& device, const Options& options) {
  if (topo.device() != &device)
    throw Error("curvature: the topology was prepared on another device");
  check_options(options, topo.vertex_count());
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
  device_call(device, "curvature", [&] { run(mesh, device, options, out, timings); });
}

void estimate(const Positions& positions, Topology& topo, Device& device, const Options& options,
              CurvatureField& out, Timings* timings) {
  const Clock::time_point start = Clock::now();
  device_call(device, "curvature", [&] {
    check_prepared(topo, device, options);
    upload_positions(positions, topo);
    const double upload_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    run_resident(topo, device, options, out, timings, start, upload_ms);
  });
}

void estimate_resident(Topology& topo, Device& device, const Options& options,
                       CurvatureField& out, Timings* timings) {
  const Clock::time_point start = Clock::now();
  device_call(device, "curvature", [&] {
    check_prepared(topo, device, options);
    run_resident(topo, device, options, out, timings, start, 0);
  });
}

}  // namespace isocurv::curvature
