#include "curvature/topology.h"

#include <algorithm>
#include <string>

#include "core/device_call.h"
#include "core/error.h"
#include "curvature/detail/local_geometry.h"
#include "curvature/detail/mesh_pass_cl.h"
#include "curvature/estimator.h"
#include "curvature/input.h"
#include "curvature/vertex_corners.h"

namespace isocurv::curvature {
namespace {

// The slots of a Topology's ScratchBuffers (qualified: estimate.cpp, which may share a unity
// batch, has slots of its own).
struct TopologySlot {
  enum : std::size_t {
  kPositions,
  kTriangles,
  kOffsets,
  kCorners,
  kLarge,
  kNbOffsets,
  kNbIds,
  kSlots
  };
};

template <class T, class A>
cl::Buffer device_copy(Device& device, ScratchBuffers& store, std::size_t slot,
                       const std::vector<T, A>& v) {
  cl::Buffer b = store.get(slot, std::max<std::size_t>(v.size() * sizeof(T), 16));
  if (!v.empty()) device.queue().enqueueWriteBuffer(b, CL_TRUE, 0, v.size() * sizeof(T), v.data());
  return b;
}

}  // namespace

Topology prepare(const Triangles& triangles, std::size_t vertex_count, Device& device) {
  check_triangles(triangles, vertex_count);
  Topology t;
  t.device_ = &device;
  t.vertex_count_ = vertex_count;
  t.triangles_ = triangles;
  Mesh shape;  // build_vertex_corners reads only the triangles and the vertex count
  shape.triangles = triangles;
  shape.positions.resize(vertex_count);
  build_vertex_corners(shape, t.adjacency_);
  std::vector<std::uint32_t> large;
  for (std::size_t v = 0; v < vertex_count; ++v)
    if (t.adjacency_.offsets[v + 1] - t.adjacency_.offsets[v] > kMaxFan)
      large.push_back(std::uint32_t(v));
  t.large_count_ = large.size();
  device_call(device, "curvature: preparing the topology", [&] {
    // Buffers like the cold path's (core/cl_scratch.h: on a CPU device, host memory in huge
    // pages), so the kernels see the same kind of memory either way.
    t.store_ = std::make_shared<ScratchBuffers>(device, TopologySlot::kSlots);
    t.positions_ =
        t.store_->get(TopologySlot::kPositions, std::max<std::size_t>(vertex_count * sizeof(Vec3f), 16));
    t.triangle_buf_ = device_copy(device, *t.store_, TopologySlot::kTriangles, triangles);
    t.offsets_buf_ = device_copy(device, *t.store_, TopologySlot::kOffsets, t.adjacency_.offsets);
    t.corners_buf_ = device_copy(device, *t.store_, TopologySlot::kCorners, t.adjacency_.corners);
    t.large_buf_ = device_copy(device, *t.store_, TopologySlot::kLarge, large);
  });
  return t;
}

const cl::Buffer& Topology::neighbour_offsets_buffer() {
  if (!have_neighbours_) {
    Mesh shape;
    shape.triangles = triangles_;
    shape.positions.resize(vertex_count_);
    const detail::Neighbours nb = detail::vertex_neighbours(shape, adjacency_);
    nb_offsets_buf_ = device_copy(*device_, *store_, TopologySlot::kNbOffsets, nb.offsets);
    nb_ids_buf_ = device_copy(*device_, *store_, TopologySlot::kNbIds, nb.ids);
    have_neighbours_ = true;
  }
  return nb_offsets_buf_;
}

const cl::Buffer& Topology::neighbour_ids_buffer() {
  neighbour_offsets_buffer();
  return nb_ids_buf_;
}

void upload_positions(const Positions& positions, Topology& topo) {
  if (!topo.device()) throw Error("curvature: the topology was never prepared");
  if (positions.size() != topo.vertex_count())
    throw Error("curvature: " + std::to_string(positions.size()) +
                " positions given for a topology of " + std::to_string(topo.vertex_count()) +
                " vertices");
  check_positions(positions);
  if (!positions.empty())
    topo.device()->queue().enqueueWriteBuffer(topo.positions(), CL_TRUE, 0,
                                              positions.size() * sizeof(Vec3f), positions.data());
}

void estimate_resident(Estimator e, Topology& topo, Device& device, const Options& options,
                       CurvatureField& out, Timings* timings) {
  switch (e) {
    case Estimator::rusinkiewicz:
      estimate_resident(topo, device, options, out, timings);
      return;
    case Estimator::batagelo:
    case Estimator::prantl3:
    case Estimator::prantl2:
      if (topo.device() != &device)
        throw Error("curvature: the topology was prepared on another device");
      check_options(options, topo.vertex_count());
      detail::estimate_resident_mesh_pass(e, topo, device, options, out, timings);
      return;
    default:
      throw Error("curvature: a prepared topology runs only " + prepared_estimator_names() + "; " +
                  no_prepared_path_reason(e));
  }
}

bool has_prepared_path(Estimator e) {
  switch (e) {
    case Estimator::rusinkiewicz:
    case Estimator::batagelo:
    case Estimator::prantl3:
    case Estimator::prantl2:
      return true;
    case Estimator::volume:
    case Estimator::quadric:
    case Estimator::cubic:
    case Estimator::sampling:
    case Estimator::meyer:
      return false;
  }
  return false;
}

std::string prepared_estimator_names() { return "rusinkiewicz, batagelo, prantl3 and prantl2"; }

std::string no_prepared_path_reason(Estimator e) {
  if (has_prepared_path(e)) return {};
  const std::string name = estimator_name(e);
  if (e == Estimator::volume)
    return name + " needs the volume the mesh was extracted from, not a mesh alone";
  return name +
         " has no prepared-topology path (a double-precision C++ reference on the host, without "
         "device kernels)";
}

}  // namespace isocurv::curvature
