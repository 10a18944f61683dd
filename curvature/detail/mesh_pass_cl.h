#pragma once
// Device state shared by the one-pass mesh estimators' kernel paths (batagelo, prantl): the
// program (curvature_math.cl + curvature_kernels.cl + mesh_estimator_kernels.cl), buffers kept
// between calls, and the first step they share with Rusinkiewicz's path (normals, mixed areas,
// boundary flags by the kernels of curvature_kernels.cl).
#include <chrono>
#include <cstdint>
#include <mutex>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/detail/local_geometry.h"
#include "curvature/estimate.h"
#include "curvature/options.h"
#include "curvature/topology.h"
#include "curvature/vertex_corners.h"

namespace isocurv::curvature::detail {

/// A device buffer kept between calls, reallocated (with 50% headroom) only when too small.
struct ClBuffer {
  cl::Buffer buffer;
  std::size_t bytes = 0;
  cl::Buffer& reserve(cl::Context& context, std::size_t need);
};

/// One per device (Device::state); `mutex` serialises calls (kernel arguments are shared state).
struct MeshPassSession {
  explicit MeshPassSession(Device& device);  ///< builds the program, makes the kernels
  std::mutex mutex;
  cl::Kernel corner_normals_areas, vertex_normals_areas, vertex_boundary, vertex_boundary_large;
  cl::Kernel batagelo_tensor, batagelo_dcurv, prantl_faces, prantl_vertices;
  ClBuffer positions, triangles, offsets, corners, large_fans, given_normals, corner;
  ClBuffer nb_offsets, nb_ids, normals, area, boundary, k1, k2, dir1, dir2, H, K, shape, curved,
      ao, dcurv, no_tensor, unreliable;
  VertexCorners adjacency;
  std::vector<std::uint32_t> large;  ///< vertices with more than kMaxFan corners
  Neighbours neighbours;             ///< host copy of the distinct 1-ring (batagelo)
};

/// The session of `device`, created (program built, kernels made) on first use.
MeshPassSession& mesh_pass_session(Device& device);

constexpr std::size_t kGroup = 64;  ///< work-group size of every launch

/// The device arrays one estimate reads: the session's (cold path) or a prepared Topology's.
/// nb_offsets and nb_ids (the distinct 1-ring) are only set where an estimator needs them.
struct MeshBuffers {
  const cl::Buffer* positions = nullptr;
  const cl::Buffer* triangles = nullptr;
  const cl::Buffer* offsets = nullptr;
  const cl::Buffer* corners = nullptr;
  const cl::Buffer* large = nullptr;
  const cl::Buffer* nb_offsets = nullptr;
  const cl::Buffer* nb_ids = nullptr;
  std::size_t nv = 0, nf = 0, large_count = 0;
};

/// Builds the adjacency (and, when with_neighbours, the distinct 1-ring) and uploads the mesh
/// into the session's buffers; t.adjacency receives the host time since `clock`, which moves on.
/// nv > 0. Call with s.mutex held.
MeshBuffers upload_mesh(MeshPassSession& s, Device& device, const Mesh& mesh,
                        bool with_neighbours, std::chrono::steady_clock::time_point& clock,
                        Timings& t);

/// Uploads the given normals, reserves the per-vertex output buffers, and runs the normal, area
/// and boundary kernels on `m`. `t` receives upload (since `clock`) and normals_areas (the latter
/// only when `timed`); clock moves on. nv > 0. Call with s.mutex held.
void normals_pass(MeshPassSession& s, Device& device, const MeshBuffers& m,
                  const Options& options, bool timed, std::chrono::steady_clock::time_point& clock,
                  Timings& t);

/// The steps after normals_pass of Batagelo's and Prantl's kernel paths, downloads included
/// (batagelo_estimate.cpp, prantl_estimate.cpp). Call with s.mutex held.
void batagelo_passes(MeshPassSession& s, Device& device, const MeshBuffers& m,
                     const Options& options, bool timed,
                     std::chrono::steady_clock::time_point& clock, Timings& t,
                     CurvatureField& out);
void prantl_passes(MeshPassSession& s, Device& device, const MeshBuffers& m,
                   const Options& options, int edges, bool area_averaging, bool timed,
                   std::chrono::steady_clock::time_point& clock, Timings& t,
                   CurvatureField& out);

/// The prepared-topology path of batagelo, prantl3 and prantl2 (topology.h), positions already
/// in topo.positions(); `out` is reset first. Options already checked.
void estimate_resident_mesh_pass(Estimator e, Topology& topo, Device& device,
                                 const Options& options, CurvatureField& out, Timings* timings);

/// Copies a device buffer of n elements into v (non-blocking; finish the queue before use).
template <class T>
void download(cl::CommandQueue& q, ClBuffer& b, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  if (n) q.enqueueReadBuffer(b.buffer, CL_FALSE, 0, n * sizeof(T), v.data());
}

/// Milliseconds since `since`, which then moves to now.
double lap_ms(std::chrono::steady_clock::time_point& since);

}  // namespace isocurv::curvature::detail
