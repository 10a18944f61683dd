// curvature::estimate_prantl: the kernel path of Prantl et al.'s per-triangle estimator.
#include <chrono>
#include <string>

#include "core/cl_launch.h"
#include "core/error.h"
#include "curvature/detail/mesh_pass_cl.h"
#include "curvature/input.h"
#include "curvature/prantl.h"

namespace isocurv::curvature {
namespace {

CurvatureField run(const Mesh& mesh, Device& device, const Options& options, int edges,
                   PrantlAveraging averaging, Timings* timings) {
  auto clock = std::chrono::steady_clock::now();
  const auto start = clock;
  check_input(mesh, options);
  if (edges != 2 && edges != 3)
    throw Error("curvature: the Prantl estimator takes 2 or 3 edges, not " +
                std::to_string(edges));
  Timings t;
  CurvatureField out;
  const std::size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  if (nv == 0) {
    if (timings) *timings = t;
    return out;
  }
  detail::MeshPassSession& s = detail::mesh_pass_session(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::CommandQueue& q = device.queue();
  const bool timed = timings != nullptr;
  detail::upload_and_normals(s, device, mesh, options, /*with_neighbours=*/false, timed, t);
  clock = std::chrono::steady_clock::now();

  set_args(s.prantl_faces, s.positions.buffer, s.triangles.buffer, s.normals.buffer,
           cl_uint(nf), cl_int(edges == 2), cl_int(averaging == PrantlAveraging::area),
           s.corner.buffer);
  launch(q, s.prantl_faces, nf, detail::kGroup);
  if (timed) q.finish();
  t.tensor = detail::lap_ms(clock);

  set_args(s.prantl_vertices, s.offsets.buffer, s.corners.buffer, s.corner.buffer, cl_uint(nv),
           cl_float(options.ao_scale), s.k1.buffer, s.k2.buffer, s.H.buffer, s.K.buffer,
           s.shape.buffer, s.curved.buffer, s.ao.buffer, s.unreliable.buffer);
  launch(q, s.prantl_vertices, nv, detail::kGroup);
  if (timed) q.finish();
  t.directions = detail::lap_ms(clock);

  detail::download(q, s.normals, out.normals, nv);
  detail::download(q, s.area, out.area, nv);
  detail::download(q, s.k1, out.k1, nv);
  detail::download(q, s.k2, out.k2, nv);
  detail::download(q, s.H, out.H, nv);
  detail::download(q, s.K, out.K, nv);
  detail::download(q, s.shape, out.shape_index, nv);
  detail::download(q, s.curved, out.curvedness, nv);
  detail::download(q, s.ao, out.ao, nv);
  detail::download(q, s.boundary, out.boundary, nv);
  detail::download(q, s.unreliable, out.unreliable, nv);
  q.finish();
  t.download = detail::lap_ms(clock);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
  return out;
}

}  // namespace

CurvatureField estimate_prantl(const Mesh& mesh, Device& device, const Options& options,
                               int edges, PrantlAveraging averaging, Timings* timings) {
  try {
    return run(mesh, device, options, edges, averaging, timings);
  } catch (const cl::Error& e) {
    detail::rethrow_cl(device, "prantl", e);
  }
}

}  // namespace isocurv::curvature
