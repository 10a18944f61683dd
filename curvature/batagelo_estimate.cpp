// curvature::estimate_batagelo: the kernel path of Batagelo & Wu's one-pass estimator.
#include <chrono>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "curvature/batagelo.h"
#include "curvature/detail/mesh_pass_cl.h"
#include "curvature/input.h"

namespace isocurv::curvature {
namespace detail {

void batagelo_passes(MeshPassSession& s, Device& device, const MeshBuffers& m,
                     const Options& options, bool timed,
                     std::chrono::steady_clock::time_point& clock, Timings& t,
                     CurvatureField& out) {
  cl::CommandQueue& q = device.queue();
  const std::size_t nv = m.nv;
  const cl_uint vcount = cl_uint(nv);
  set_args(s.batagelo_tensor, *m.positions, s.normals.buffer, *m.nb_offsets, *m.nb_ids, vcount,
           cl_float(options.ao_scale),
           cl_uint(options.batagelo_weights == NeighbourWeights::inverse_square), s.k1.buffer, s.k2.buffer, s.dir1.buffer, s.dir2.buffer,
           s.H.buffer, s.K.buffer, s.shape.buffer, s.curved.buffer, s.ao.buffer,
           s.no_tensor.buffer);
  launch(q, s.batagelo_tensor, nv, kGroup);
  if (timed) q.finish();
  t.tensor = lap_ms(clock);

  set_args(s.batagelo_dcurv, *m.positions, s.k1.buffer, s.k2.buffer, s.dir1.buffer,
           s.dir2.buffer, *m.nb_offsets, *m.nb_ids, s.no_tensor.buffer, vcount, s.dcurv.buffer,
           s.unreliable.buffer);
  launch(q, s.batagelo_dcurv, nv, kGroup);
  if (timed) q.finish();
  t.derivative = lap_ms(clock);

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
  download(q, s.unreliable, out.unreliable, nv);
  q.finish();
  t.download = lap_ms(clock);
}

}  // namespace detail

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
  const bool timed = timings != nullptr;
  const detail::MeshBuffers m =
      detail::upload_mesh(s, device, mesh, /*with_neighbours=*/true, clock, t);
  detail::normals_pass(s, device, m, options, timed, clock, t);
  detail::batagelo_passes(s, device, m, options, timed, clock, t, out);
  t.total = std::chrono::duration<double, std::milli>(clock - start).count();
  if (timings) *timings = t;
  return out;
}

}  // namespace

CurvatureField estimate_batagelo(const Mesh& mesh, Device& device, const Options& options,
                                 Timings* timings) {
  return device_call(device, "curvature: batagelo", [&] { return run(mesh, device, options, timings); });
}

}  // namespace isocurv::curvature
