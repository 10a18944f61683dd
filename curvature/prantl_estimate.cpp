// curvature::estimate_prantl: the kernel path of Prantl et al.'s per-triangle estimator.
#include <chrono>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "curvature/detail/mesh_pass_cl.h"
#include "curvature/input.h"
#include "curvature/prantl.h"

namespace isocurv::curvature {
namespace detail {

void prantl_passes(MeshPassSession& s, Device& device, const MeshBuffers& m,
                   const Options& options, int edges, bool area_averaging, bool timed,
                   std::chrono::steady_clock::time_point& clock, Timings& t,
                   CurvatureField& out) {
  cl::CommandQueue& q = device.queue();
  const std::size_t nv = m.nv, nf = m.nf;
  set_args(s.prantl_faces, *m.positions, *m.triangles, s.normals.buffer, cl_uint(nf),
           cl_int(edges == 2), cl_int(area_averaging), s.corner.buffer);
  launch(q, s.prantl_faces, nf, kGroup);
  if (timed) q.finish();
  t.tensor = lap_ms(clock);

  set_args(s.prantl_vertices, *m.offsets, *m.corners, s.corner.buffer, cl_uint(nv),
           cl_float(options.ao_scale), s.k1.buffer, s.k2.buffer, s.H.buffer, s.K.buffer,
           s.shape.buffer, s.curved.buffer, s.ao.buffer, s.unreliable.buffer);
  launch(q, s.prantl_vertices, nv, kGroup);
  if (timed) q.finish();
  t.directions = lap_ms(clock);

  download(q, s.normals, out.normals, nv);
  download(q, s.area, out.area, nv);
  download(q, s.k1, out.k1, nv);
  download(q, s.k2, out.k2, nv);
  download(q, s.H, out.H, nv);
  download(q, s.K, out.K, nv);
  download(q, s.shape, out.shape_index, nv);
  download(q, s.curved, out.curvedness, nv);
  download(q, s.ao, out.ao, nv);
  download(q, s.boundary, out.boundary, nv);
  download(q, s.unreliable, out.unreliable, nv);
  q.finish();
  t.download = lap_ms(clock);
}

}  // namespace detail

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
  const std::size_t nv = mesh.vertex_count();
  if (nv == 0) {
    if (timings) *timings = t;
    return out;
  }
  detail::MeshPassSession& s = detail::mesh_pass_session(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  const bool timed = timings != nullptr;
  const detail::MeshBuffers m =
      detail::upload_mesh(s, device, mesh, /*with_neighbours=*/false, clock, t);
  detail::normals_pass(s, device, m, options, timed, clock, t);
  detail::prantl_passes(s, device, m, options, edges, averaging == PrantlAveraging::area, timed,
                        clock, t, out);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
  return out;
}

}  // namespace

CurvatureField estimate_prantl(const Mesh& mesh, Device& device, const Options& options,
                               int edges, PrantlAveraging averaging, Timings* timings) {
  return device_call(device, "curvature: prantl",
                     [&] { return run(mesh, device, options, edges, averaging, timings); });
}

}  // namespace isocurv::curvature
