#pragma once
// curvature::Topology: a mesh's connectivity prepared once for per-frame curvature of a deforming
// mesh (Griffin et al. 2012 section 3.4: the triangles never change, only the positions do).
// Tested in tests/deform/animation_test.cpp, tests/deform/prepared_test.cpp.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/cl_scratch.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/estimate.h"
#include "curvature/options.h"
#include "curvature/vertex_corners.h"

namespace isocurv::curvature {

/// The fixed part of a deforming mesh on one device: the triangles, the vertex -> corner CSR
/// (vertex_corners.h), the list of large fans (more than 8 corners) and, for the one-pass
/// estimators, the distinct 1-ring; all built once on the host and uploaded once into device
/// buffers this object owns. It also owns the device buffer of positions the prepared estimates
/// read (positions()): a deformer (deform/) writes it directly so an animated mesh need never
/// cross to the host. Move-only in spirit (copies share the device buffers). Tied to the device
/// it was prepared on, which must outlive it. Not thread-safe: one frame at a time.
class Topology {
 public:
  Topology() = default;
  std::size_t vertex_count() const { return vertex_count_; }
  std::size_t triangle_count() const { return triangles_.size(); }
  const Triangles& triangles() const { return triangles_; }
  const VertexCorners& adjacency() const { return adjacency_; }
  Device* device() const { return device_; }

  /// Device buffer of vertex_count() positions, packed float x, y, z (12 bytes each, world
  /// units): what estimate_resident() reads and estimate(positions, ...) overwrites.
  cl::Buffer& positions() { return positions_; }

  // Device copies of the fixed arrays (read by the estimators' host code).
  const cl::Buffer& triangle_buffer() const { return triangle_buf_; }
  const cl::Buffer& offsets_buffer() const { return offsets_buf_; }
  const cl::Buffer& corners_buffer() const { return corners_buf_; }
  const cl::Buffer& large_fans_buffer() const { return large_buf_; }
  std::size_t large_fan_count() const { return large_count_; }
  /// The distinct 1-ring (Batagelo's estimator), uploaded on first use.
  const cl::Buffer& neighbour_offsets_buffer();
  const cl::Buffer& neighbour_ids_buffer();

 private:
  friend Topology prepare(const Triangles& triangles, std::size_t vertex_count, Device& device);
  Device* device_ = nullptr;
  std::shared_ptr<ScratchBuffers> store_;  // the buffers' memory (huge pages on CPU devices)
  std::size_t vertex_count_ = 0, large_count_ = 0;
  Triangles triangles_;
  VertexCorners adjacency_;
  cl::Buffer positions_, triangle_buf_, offsets_buf_, corners_buf_, large_buf_;
  bool have_neighbours_ = false;
  cl::Buffer nb_offsets_buf_, nb_ids_buf_;
};

/// Prepares `triangles` over `vertex_count` vertices on `device`: checks them (check_triangles),
/// builds the adjacency and large-fan list as estimate() would, and uploads them. The positions
/// buffer is allocated but unset.
/// @throw isocurv::Error for an index out of range, too large a mesh, or an OpenCL failure
Topology prepare(const Triangles& triangles, std::size_t vertex_count, Device& device);

/// Rusinkiewicz's estimator (estimate.h) of the mesh (positions, topo's triangles): uploads only
/// `positions` (and options.vertex_normals when given) and reuses topo's adjacency. The output
/// is bit-identical to estimate(Mesh{positions, triangles}, device, options): the same kernels
/// with the same arguments. timings->adjacency is 0 (nothing is rebuilt).
/// @param device must be topo.device()
/// @throw isocurv::Error for positions of the wrong count or non-finite (check_positions), bad
///        options (check_options), another device, or an OpenCL failure
void estimate(const Positions& positions, Topology& topo, Device& device, const Options& options,
              CurvatureField& out, Timings* timings = nullptr);

/// The same from the positions already in topo.positions() (written by a deformer): nothing but
/// the given normals crosses to the device. The positions are not checked: non-finite ones give
/// non-finite curvature.
void estimate_resident(Topology& topo, Device& device, const Options& options, CurvatureField& out,
                       Timings* timings = nullptr);

/// Batagelo's and Prantl's kernel paths (batagelo.h, prantl.h; e is one of batagelo, prantl3,
/// prantl2, Prantl's variants averaging by area, or rusinkiewicz) on the positions in
/// topo.positions(): bit-identical to estimate_mesh(e, mesh, &device, options) of those
/// positions. Arrays the estimator does not produce stay empty.
/// @throw isocurv::Error for an estimator without a kernel path, another device, bad options or
///        an OpenCL failure
void estimate_resident(Estimator e, Topology& topo, Device& device, const Options& options,
                       CurvatureField& out, Timings* timings = nullptr);

/// True for the estimators with a prepared path (estimate_resident): rusinkiewicz, batagelo,
/// prantl3 and prantl2, the mesh estimators with kernels. The others have none: volume needs the
/// volume, not only a mesh; quadric, cubic, sampling and meyer are double-precision C++ references
/// on the host (no kernels) that build their own 1-ring from the mesh on every call, so a
/// "prepared" path for them would only be a cold estimate per frame.
bool has_prepared_path(Estimator e);

/// The names of the estimators with a prepared path, for messages: "rusinkiewicz, batagelo,
/// prantl3 and prantl2".
std::string prepared_estimator_names();

/// Why `e` has no prepared path, one clause that starts with its name ("quadric has no
/// prepared-topology path (...)"), for the one-line errors of estimate_resident, isocurv deform
/// and the Python Topology, which add the estimators that have one; empty when it has one.
std::string no_prepared_path_reason(Estimator e);

/// Uploads `positions` into topo.positions() (blocking), after check_positions and a count check.
void upload_positions(const Positions& positions, Topology& topo);

}  // namespace isocurv::curvature
