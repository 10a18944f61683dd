#include "curvature/detail/mesh_pass_cl.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/detail/math_options.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"
#include "curvature/vertex_corners.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const curvature_kernels_cl;
extern const char* const mesh_estimator_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature::detail {
namespace {

const std::string& program_source() {
  static const std::string source = std::string(kernels::curvature_math_cl) + "\n" +
                                    kernels::curvature_kernels_cl + "\n" +
                                    kernels::mesh_estimator_kernels_cl;
  return source;
}

std::string build_options() {
  return math_build_options() + " -DMAX_FAN=" + std::to_string(kMaxFan);
}

template <class T, class A>
void upload(cl::CommandQueue& q, cl::Context& ctx, ClBuffer& b, const std::vector<T, A>& v) {
  b.reserve(ctx, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b.buffer, CL_FALSE, 0, v.size() * sizeof(T), v.data());
}

}  // namespace

cl::Buffer& ClBuffer::reserve(cl::Context& context, std::size_t need) {
  need = std::max<std::size_t>(need, 16);
  if (need > bytes) {
    bytes = std::max(need, bytes + bytes / 2);
    buffer = cl::Buffer(context, CL_MEM_READ_WRITE, bytes);
  }
  return buffer;
}

MeshPassSession::MeshPassSession(Device& device) {
  cl::Program& program =
      device.program("curvature_mesh_estimators", program_source().c_str(), build_options());
  corner_normals_areas = cl::Kernel(program, "corner_normals_areas");
  vertex_normals_areas = cl::Kernel(program, "vertex_normals_areas");
  vertex_boundary = cl::Kernel(program, "vertex_boundary");
  vertex_boundary_large = cl::Kernel(program, "vertex_boundary_large");
  batagelo_tensor = cl::Kernel(program, "batagelo_tensor");
  batagelo_dcurv = cl::Kernel(program, "batagelo_dcurv");
  prantl_faces = cl::Kernel(program, "prantl_faces");
  prantl_vertices = cl::Kernel(program, "prantl_vertices");
}

MeshPassSession& mesh_pass_session(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<MeshPassSession>();
}

double lap_ms(std::chrono::steady_clock::time_point& since) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - since).count();
  since = now;
  return ms;
}

MeshBuffers upload_mesh(MeshPassSession& s, Device& device, const Mesh& mesh,
                        bool with_neighbours, std::chrono::steady_clock::time_point& clock,
                        Timings& t) {
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  build_vertex_corners(mesh, s.adjacency);
  s.large.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (s.adjacency.offsets[v + 1] - s.adjacency.offsets[v] > kMaxFan)
      s.large.push_back(std::uint32_t(v));
  if (with_neighbours) s.neighbours = vertex_neighbours(mesh, s.adjacency);
  t.adjacency = lap_ms(clock);

  upload(q, ctx, s.positions, mesh.positions);
  upload(q, ctx, s.triangles, mesh.triangles);
  upload(q, ctx, s.offsets, s.adjacency.offsets);
  upload(q, ctx, s.corners, s.adjacency.corners);
  upload(q, ctx, s.large_fans, s.large);
  MeshBuffers m;
  if (with_neighbours) {
    upload(q, ctx, s.nb_offsets, s.neighbours.offsets);
    upload(q, ctx, s.nb_ids, s.neighbours.ids);
    m.nb_offsets = &s.nb_offsets.buffer;
    m.nb_ids = &s.nb_ids.buffer;
  }
  m.positions = &s.positions.buffer;
  m.triangles = &s.triangles.buffer;
  m.offsets = &s.offsets.buffer;
  m.corners = &s.corners.buffer;
  m.large = &s.large_fans.buffer;
  m.nv = nv, m.nf = nf, m.large_count = s.large.size();
  return m;
}

void normals_pass(MeshPassSession& s, Device& device, const MeshBuffers& m,
                  const Options& options, bool timed, std::chrono::steady_clock::time_point& clock,
                  Timings& t) {
  const std::size_t nv = m.nv, nf = m.nf;
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  const bool given = options.vertex_normals != nullptr;
  if (given)
    upload(q, ctx, s.given_normals, *options.vertex_normals);
  else
    s.given_normals.reserve(ctx, 16);
  s.corner.reserve(ctx, 3 * nf * sizeof(cl_float4));
  for (ClBuffer* b : {&s.area, &s.k1, &s.k2, &s.H, &s.K, &s.shape, &s.curved, &s.ao})
    b->reserve(ctx, nv * sizeof(float));
  for (ClBuffer* b : {&s.normals, &s.dir1, &s.dir2}) b->reserve(ctx, nv * sizeof(Vec3f));
  for (ClBuffer* b : {&s.boundary, &s.no_tensor, &s.unreliable}) b->reserve(ctx, nv);
  s.dcurv.reserve(ctx, nv * sizeof(cl_float4));
  if (timed) q.finish();
  t.upload = lap_ms(clock);

  const cl_uint vcount = cl_uint(nv), fcount = cl_uint(nf), lcount = cl_uint(m.large_count);
  set_args(s.corner_normals_areas, *m.positions, *m.triangles, fcount,
           cl_int(options.normal_weights == NormalWeights::area), s.corner.buffer);
  launch(q, s.corner_normals_areas, nf, kGroup);
  set_args(s.vertex_normals_areas, *m.offsets, *m.corners, s.corner.buffer,
           s.given_normals.buffer, cl_int(given), vcount, s.normals.buffer, s.area.buffer);
  launch(q, s.vertex_normals_areas, nv, kGroup);
  set_args(s.vertex_boundary, *m.offsets, *m.corners, *m.triangles, vcount, s.boundary.buffer);
  launch(q, s.vertex_boundary, nv, kGroup);
  set_args(s.vertex_boundary_large, *m.offsets, *m.corners, *m.triangles, *m.large, lcount,
           s.boundary.buffer);
  launch(q, s.vertex_boundary_large, m.large_count, kGroup);
  if (timed) q.finish();
  t.normals_areas = lap_ms(clock);
}

void estimate_resident_mesh_pass(Estimator e, Topology& topo, Device& device,
                                 const Options& options, CurvatureField& out, Timings* timings) {
  const auto start = std::chrono::steady_clock::now();
  auto clock = start;
  Timings t;
  out = CurvatureField{};
  const std::size_t nv = topo.vertex_count();
  if (nv == 0) {
    if (timings) *timings = t;
    return;
  }
  const bool batagelo = e == Estimator::batagelo;
  device_call(device, batagelo ? "curvature: batagelo" : "curvature: prantl", [&] {
    MeshBuffers m;
    m.positions = &topo.positions();
    m.triangles = &topo.triangle_buffer();
    m.offsets = &topo.offsets_buffer();
    m.corners = &topo.corners_buffer();
    m.large = &topo.large_fans_buffer();
    if (batagelo) {
      m.nb_offsets = &topo.neighbour_offsets_buffer();
      m.nb_ids = &topo.neighbour_ids_buffer();
    }
    m.nv = nv, m.nf = topo.triangle_count(), m.large_count = topo.large_fan_count();
    MeshPassSession& s = mesh_pass_session(device);
    std::lock_guard<std::mutex> lock(s.mutex);
    const bool timed = timings != nullptr;
    normals_pass(s, device, m, options, timed, clock, t);
    if (batagelo)
      batagelo_passes(s, device, m, options, timed, clock, t, out);
    else
      prantl_passes(s, device, m, options, e == Estimator::prantl3 ? 3 : 2, /*area=*/true, timed,
                    clock, t, out);
  });
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
}
}  // namespace isocurv::curvature::detail
