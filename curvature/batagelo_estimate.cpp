// curvature::estimate_batagelo: the kernel path of Batagelo & Wu's one-pass estimator.
#include <chrono>

#include "core/cl_launch.h"
#include "curvature/batagelo.h"
#include "curvature/detail/mesh_pass_cl.h"
#include "curvature/input.h"

namespace isocurv::curvature {
namespace {

CurvatureField run(const Mesh& mesh, Device& device, const Options& options, Timings* timings) {
  auto clock = std::chrono::steady_clock::now();
  const auto start = clock;
  check_input(mesh, options);
  Timings t;
  CurvatureField out;
  const std::size_t nv = mesh.vertex_count();
  if (nv == 0) {
    if (timings) *timings = t;
    return out;
  }
  detail::MeshPassSession& s = detail::mesh_pass_session(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  cl::CommandQueue& q = device.queue();
  const bool timed = timings != nullptr;
  detail::upload_and_normals(s, device, mesh, options, /*with_neighbours=*/true, timed, t);
  clock = std::chrono::steady_clock::now();

  const cl_uint vcount = cl_uint(nv);
  set_args(s.batagelo_tensor, s.positions.buffer, s.normals.buffer, s.nb_offsets.buffer,
           s.nb_ids.buffer, vcount, cl_float(options.ao_scale), s.k1.buffer, s.k2.buffer,
           s.dir1.buffer, s.dir2.buffer, s.H.buffer, s.K.buffer, s.shape.buffer, s.curved.buffer,
           s.ao.buffer, s.no_tensor.buffer);
  launch(q, s.batagelo_tensor, nv, detail::kGroup);
  if (timed) q.finish();
  t.tensor = detail::lap_ms(clock);

  set_args(s.batagelo_dcurv, s.positions.buffer, s.k1.buffer, s.k2.buffer, s.dir1.buffer,
           s.dir2.buffer, s.nb_offsets.buffer, s.nb_ids.buffer, s.no_tensor.buffer, vcount,
           s.dcurv.buffer, s.unreliable.buffer);
  launch(q, s.batagelo_dcurv, nv, detail::kGroup);
  if (timed) q.finish();
  t.derivative = detail::lap_ms(clock);

  detail::download(q, s.normals, out.normals, nv);
  detail::download(q, s.area, out.area, nv);
  detail::download(q, s.k1, out.k1, nv);
  detail::download(q, s.k2, out.k2, nv);
  detail::download(q, s.dir1, out.dir1, nv);
  detail::download(q, s.dir2, out.dir2, nv);
  detail::download(q, s.H, out.H, nv);
  detail::download(q, s.K, out.K, nv);
  detail::download(q, s.dcurv, out.dcurv, nv);
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

CurvatureField estimate_batagelo(const Mesh& mesh, Device& device, const Options& options,
                                 Timings* timings) {
  try {
    return run(mesh, device, options, timings);
  } catch (const cl::Error& e) {
    detail::rethrow_cl(device, "batagelo", e);
  }
}

}  // namespace isocurv::curvature
