#include "lines/extract.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "core/cl_input.h"
#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "lines/detail/vertex_pairs.h"

namespace isocurv::kernels {
extern const char* const lines_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::lines {
namespace {

using Clock = StepClock;
constexpr std::size_t kGroup = 64;          // work-group size of every launch (core/cl_launch.h)
constexpr int kMaxSegmentsPerFace = 4;      // one per line type
constexpr std::uint32_t kNoSegment = 0xff;  // NO_SEGMENT: the type of an emitting slot left empty

// A device buffer kept between calls, reallocated (with 50% headroom) only when
// too small.
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

std::string build_options();

// What extract keeps on a device between calls (Device::state): the kernels, the buffers, the
// host storage of the downloads.
struct Session {
  explicit Session(Device& device) {
    cl::Program& program = device.program("lines", kernels::lines_kernels_cl, build_options());
    vertex_view = cl::Kernel(program, "line_vertex_view");
    vertex_smooth = cl::Kernel(program, "line_vertex_smooth");
    vertex_flags = cl::Kernel(program, "line_vertex_flags");
    face_count = cl::Kernel(program, "line_face_count");
    face_emit = cl::Kernel(program, "line_face_emit");
  }
  std::mutex mutex;  // one extract at a time per device (kernel arguments are shared state)
  cl::Kernel vertex_view, vertex_smooth, vertex_flags, face_count, face_emit;
  // The call's inputs: read in place on CPU devices, copies elsewhere.
  InputBuffer triangles, positions, normals, dir1, dir2, k1, k2, dcurv;
  Buffer view, kn, kn2, flags, counts, faces, offsets;
  // What the smoothing averages over (lines/detail/vertex_pairs.h), once per mesh.
  detail::VertexPairs pairs;
  InputBuffer pair_offsets, pair_indices;
  bool have_pairs = false;
  Buffer out_a, out_b, out_edges, out_face_type;
  std::size_t uploaded_vertices = 0, uploaded_faces = 0;
  bool uploaded_dcurv = false;
  std::vector<std::uint8_t> counts_host;
  std::vector<std::uint32_t> faces_host, offsets_host;
  std::vector<cl_float4> a_host, b_host;
  std::vector<cl_ulong2> edges_host;
  std::vector<cl_uint2> face_type_host;
};

std::string build_options() {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "-DTYPE_CONTOUR=%d -DTYPE_SUGGESTIVE=%d -DTYPE_RIDGE=%d -DTYPE_VALLEY=%d "
                "-DMAX_SEGMENTS=%d -DNO_SEGMENT=%uu -DNO_EDGE=0x%llxUL "
                "-DVERTEX_SNAP=%.9gf",
                int(LineType::contour), int(LineType::suggestive), int(LineType::ridge),
                int(LineType::valley), kMaxSegmentsPerFace, unsigned(kNoSegment),
                (unsigned long long)kInsideFace, kVertexSnap);
  return buf;
}

// The session of `device`, created (program built, kernels made) on first use.
Session& session_for(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<Session>();
}

template <class T, class A>
void upload(cl::CommandQueue& q, cl::Context& ctx, Buffer& b, const std::vector<T, A>& v) {
  b.reserve(ctx, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b.buffer, CL_FALSE, 0, v.size() * sizeof(T), v.data());
}

Segments run(const Mesh& mesh, const curvature::CurvatureField& field, const Camera& camera,
             const Options& options, Device& device, Timings* timings, bool upload_mesh) {
  Clock::time_point clock = Clock::now();
  const Clock::time_point start = clock;
  Timings t;
  check_input(mesh, field, options);
  const Thresholds th = resolve_thresholds(field, options);
  t.checks = lap(clock);
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  Segments out;
  if (nv == 0 || nf == 0 || !options.lines.any()) {
    if (timings) *timings = t;
    return out;
  }
  Session& s = session_for(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  const bool with_dcurv = options.lines.needs_dcurv();
  if (!upload_mesh &&
      (s.uploaded_vertices != nv || s.uploaded_faces != nf || (with_dcurv && !s.uploaded_dcurv)))
    upload_mesh = true;  // nothing (or something else) is on the device
  if (upload_mesh) s.have_pairs = false;
  // Rebound on every call where the buffers wrap the caller's arrays (nothing is copied), so a
  // call never reads arrays that an earlier caller has since freed.
  if (upload_mesh || works_in_host_memory(device)) {
    s.triangles.bind(device, mesh.triangles);
    s.positions.bind(device, mesh.positions);
    s.normals.bind(device, field.normals);
    s.dir1.bind(device, field.dir1);  // empty for contours from a field without directions
    s.dir2.bind(device, field.dir2);
    s.k1.bind(device, field.k1);
    s.k2.bind(device, field.k2);
    static const decltype(field.dcurv) kNoDcurv;
    s.dcurv.bind(device, with_dcurv ? field.dcurv : kNoDcurv);  // a reference either way
    s.uploaded_vertices = nv, s.uploaded_faces = nf, s.uploaded_dcurv = with_dcurv;
  }
  const bool smooth = options.lines.suggestive && options.smoothing_steps > 0;
  s.view.reserve(ctx, nv * sizeof(cl_float4));
  s.kn.reserve(ctx, nv * sizeof(cl_float2));
  if (smooth) s.kn2.reserve(ctx, nv * sizeof(cl_float2));
  s.counts.reserve(ctx, nf);
  if (timings) q.finish();
  t.upload = lap(clock);

  const cl_float4 eye = {{float(camera.position[0]), float(camera.position[1]),
                          float(camera.position[2]), camera.ortho ? 1.0f : 0.0f}};
  const auto toward = camera.toward_camera();
  const cl_float4 towards = {{float(toward[0]), float(toward[1]), float(toward[2]), 0}};
  const LineSelection& sel = options.lines;
  const cl_int4 selection = {{sel.contours, sel.suggestive, sel.ridges, sel.valleys}};
  const cl_float4 thresholds = {{float(th.suggestive), float(th.cos_angle), float(th.ridge), 0}};
  if (sel.view_dependent()) {
    set_args(s.vertex_view, *s.positions.bound(), *s.normals.bound(), *s.dir1.bound(),
             *s.dir2.bound(), *s.k1.bound(), *s.k2.bound(), *s.dcurv.bound(),
             cl_int(sel.suggestive), cl_int(with_dcurv), cl_int(!field.dir1.empty()), cl_uint(nv),
             eye, towards, s.view.buffer, s.kn.buffer);
    launch(q, s.vertex_view, nv, kGroup);
  }
  if (smooth && !s.have_pairs) {
    // Built on the host while the device computes the view quantities (unless timed).
    if (timings)
      q.finish(), t.view = lap(clock);
    else
      q.flush();
    detail::build_vertex_pairs(mesh, s.pairs);
    s.pair_offsets.bind(device, s.pairs.offsets);
    s.pair_indices.bind(device, s.pairs.pairs);
    s.have_pairs = true;
    if (timings) t.ring = lap(clock);
  }
  if (smooth) {
    Buffer *in = &s.kn, *out = &s.kn2;
    for (int step = 0; step < options.smoothing_steps; ++step) {
      const cl_int last = step + 1 == options.smoothing_steps;
      set_args(s.vertex_smooth, *s.pair_offsets.bound(), *s.pair_indices.bound(), in->buffer,
               cl_uint(nv), last, out->buffer, s.view.buffer);
      launch(q, s.vertex_smooth, nv, kGroup);
      std::swap(in, out);
    }
  }
  if (timings) q.finish();
  t.view += lap(clock);
  s.flags.reserve(ctx, nv);
  set_args(s.vertex_flags, s.view.buffer, *s.k1.bound(), *s.k2.bound(), selection, thresholds,
           cl_uint(nv), s.flags.buffer);
  launch(q, s.vertex_flags, nv, kGroup);
  set_args(s.face_count, *s.triangles.bound(), s.flags.buffer, *s.dir1.bound(), *s.dir2.bound(),
           *s.dcurv.bound(), selection, thresholds, cl_uint(nf), s.counts.buffer);
  launch(q, s.face_count, nf, kGroup);
  s.counts_host.resize(nf);
  q.enqueueReadBuffer(s.counts.buffer, CL_TRUE, 0, nf, s.counts_host.data());
  t.count = lap(clock);

  // Faces with slots, in order, and where their slots start (one entry more: the end).
  s.faces_host.clear();
  s.offsets_host.clear();
  std::uint32_t total = 0;
  const std::uint8_t* counts = s.counts_host.data();
  for (std::size_t f = 0; f < nf; ++f) {
    if (f % 8 == 0 && f + 8 <= nf) {  // nearly every face has none: skip eight at a time
      std::uint64_t eight;
      std::memcpy(&eight, counts + f, sizeof eight);
      if (eight == 0) {
        f += 7;
        continue;
      }
    }
    if (counts[f] == 0) continue;
    s.faces_host.push_back(std::uint32_t(f));
    s.offsets_host.push_back(total);
    total += counts[f];
  }
  s.offsets_host.push_back(total);
  if (total > 0) {
    const std::size_t listed = s.faces_host.size();
    upload(q, ctx, s.faces, s.faces_host);
    upload(q, ctx, s.offsets, s.offsets_host);
    s.out_a.reserve(ctx, total * sizeof(cl_float4));
    s.out_b.reserve(ctx, total * sizeof(cl_float4));
    s.out_edges.reserve(ctx, total * sizeof(cl_ulong2));
    s.out_face_type.reserve(ctx, total * sizeof(cl_uint2));
    set_args(s.face_emit, *s.triangles.bound(), *s.positions.bound(), *s.normals.bound(),
             *s.dir1.bound(), *s.dir2.bound(), *s.k1.bound(), *s.k2.bound(), *s.dcurv.bound(),
             s.view.buffer, selection, thresholds, s.faces.buffer, s.offsets.buffer,
             cl_uint(listed), s.out_a.buffer, s.out_b.buffer, s.out_edges.buffer,
             s.out_face_type.buffer);
    launch(q, s.face_emit, listed, kGroup);
    s.a_host.resize(total);
    s.b_host.resize(total);
    s.edges_host.resize(total);
    s.face_type_host.resize(total);
    q.enqueueReadBuffer(s.out_a.buffer, CL_FALSE, 0, total * sizeof(cl_float4), s.a_host.data());
    q.enqueueReadBuffer(s.out_b.buffer, CL_FALSE, 0, total * sizeof(cl_float4), s.b_host.data());
    q.enqueueReadBuffer(s.out_edges.buffer, CL_FALSE, 0, total * sizeof(cl_ulong2),
                        s.edges_host.data());
    q.enqueueReadBuffer(s.out_face_type.buffer, CL_FALSE, 0, total * sizeof(cl_uint2),
                        s.face_type_host.data());
    q.finish();
    out.reserve(total);
    for (std::uint32_t i = 0; i < total; ++i) {
      if (s.face_type_host[i].s[1] == kNoSegment) continue;  // a slot left empty
      Segment& g = out.emplace_back();
      const cl_float4 &a = s.a_host[i], &b = s.b_host[i];
      g.a = {a.s[0], a.s[1], a.s[2]};
      g.b = {b.s[0], b.s[1], b.s[2]};
      g.strength = a.s[3];
      g.edge_a = s.edges_host[i].s[0];
      g.edge_b = s.edges_host[i].s[1];
      g.face = s.face_type_host[i].s[0];
      g.type = LineType(s.face_type_host[i].s[1]);
    }
  }
  // The queue is drained: let go of the caller's arrays.
  for (InputBuffer* b :
       {&s.triangles, &s.positions, &s.normals, &s.dir1, &s.dir2, &s.k1, &s.k2, &s.dcurv})
    b->release();
  t.emit = lap(clock);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
  return out;
}

}  // namespace

Segments extract(const Mesh& mesh, const curvature::CurvatureField& field, const Camera& camera,
                 const Options& options, Device& device, Timings* timings, bool upload_mesh) {
  return device_call(device, "lines",
                     [&] { return run(mesh, field, camera, options, device, timings, upload_mesh); });
}

}  // namespace isocurv::lines
