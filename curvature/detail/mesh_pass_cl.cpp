#include "curvature/detail/mesh_pass_cl.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "core/cl_launch.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/input.h"
#include "curvature/tolerances.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const curvature_kernels_cl;
extern const char* const mesh_estimator_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature::detail {
namespace {

// Fans up to this many corners are checked for boundary edges in registers (vertex_boundary);
// the same value as the Rusinkiewicz path's.
constexpr std::uint32_t kMaxFan = 8;

const std::string& program_source() {
  static const std::string source = std::string(kernels::curvature_math_cl) + "\n" +
                                    kernels::curvature_kernels_cl + "\n" +
                                    kernels::mesh_estimator_kernels_cl;
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

MeshPassSession& mesh_pass_session(Device& device) {
  static std::mutex registry_mutex;
  static std::vector<std::unique_ptr<MeshPassSession>> sessions;
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (auto& s : sessions)
    if (s->context() == device.context()()) return *s;
  auto s = std::make_unique<MeshPassSession>();
  s->context = device.context();
  cl::Program& program =
      device.program("curvature_mesh_estimators", program_source().c_str(), build_options());
  s->corner_normals_areas = cl::Kernel(program, "corner_normals_areas");
  s->vertex_normals_areas = cl::Kernel(program, "vertex_normals_areas");
  s->vertex_boundary = cl::Kernel(program, "vertex_boundary");
  s->vertex_boundary_large = cl::Kernel(program, "vertex_boundary_large");
  s->batagelo_tensor = cl::Kernel(program, "batagelo_tensor");
  s->batagelo_dcurv = cl::Kernel(program, "batagelo_dcurv");
  s->prantl_faces = cl::Kernel(program, "prantl_faces");
  s->prantl_vertices = cl::Kernel(program, "prantl_vertices");
  sessions.push_back(std::move(s));
  return *sessions.back();
}

double lap_ms(std::chrono::steady_clock::time_point& since) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - since).count();
  since = now;
  return ms;
}

void upload_and_normals(MeshPassSession& s, Device& device, const Mesh& mesh,
                        const Options& options, bool with_neighbours, bool timed, Timings& t) {
  auto clock = std::chrono::steady_clock::now();
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
  if (with_neighbours) {
    upload(q, ctx, s.nb_offsets, s.neighbours.offsets);
    upload(q, ctx, s.nb_ids, s.neighbours.ids);
  }
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
  if (timed) q.finish();
  t.normals_areas = lap_ms(clock);
}

void rethrow_cl(Device& device, const char* what, const cl::Error& e) {
  try {
    device.queue().finish();  // no copy may still target the field being unwound
  } catch (const cl::Error&) {
  }
  throw Error(std::string("curvature: ") + what + ": OpenCL call " + e.what() + " failed on " +
              device.info().name + ": " + cl_error_name(e.err()));
}

}  // namespace isocurv::curvature::detail
