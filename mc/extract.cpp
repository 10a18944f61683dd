#include "mc/extract.h"

#include <chrono>
#include <optional>
#include <string>

#include "core/cl_device.h"
#include "core/device_call.h"
#include "core/error.h"
#include "mc/bricks.h"
#include "mc/detail/mesher_passes.h"
#include "mc/frame.h"
#include "mc/snap_vertices.h"
#include "mc/triangle_quality.h"

namespace isocurv::mc {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace

struct Mesher::State {
  const volume::Volume& volume;
  Device& device;
  BrickIndex index;
  std::optional<detail::MesherTables> tables;
  State(const volume::Volume& v, Device& d) : volume(v), device(d), index(v) {}
};

Mesher::Mesher(const volume::Volume& v, Device& device) : state_(std::make_unique<State>(v, device)) {
  device_call(device, "marching cubes: setup", [&] { state_->tables.emplace(device); });
}

Mesher::~Mesher() = default;

// The driver: each step one pass of mc/detail/mesher_passes.h, in the order of the fused
// marching cubes.
Mesh Mesher::extract(float isovalue, const Options& options, ExtractTimings* timings) {
  State& st = *state_;
  ExtractTimings tm;
  const auto t0 = Clock::now();
  const Frame f = make_frame(st.volume, isovalue, options);
  // The bricks that may hold surface, from the per-block value ranges (host).
  std::vector<openvdb::Coord> origins = st.index.candidates(f);
  tm.select = ms_since(t0);
  const auto t1 = Clock::now();
  auto t2 = t1, step = t1;
  Mesh mesh;
  // With timings requested, drain the queue after each step and charge it its wall time.
  const detail::Mark mark = [&](double ExtractTimings::*field) {
    if (!timings) return;
    st.device.queue().finish();
    tm.*field += ms_since(step);
    step = Clock::now();
  };
  if (!origins.empty()) {
    // Kernels may still write into the mesh's vectors and read x's host arrays: device_call
    // drains the queue before the mesh unwinds, `drain` before x does.
    const std::string& path = st.volume.path;
    device_call(st.device, path.empty() ? "marching cubes" : path + ": marching cubes", [&] {
      detail::Extraction x{st.device, *st.tables, f, options, path};
      const DrainOnUnwind drain(st.device);
      // 1. their samples with aprons, on the device
      detail::gather_samples(x, st.index, origins);
      tm.gather = ms_since(t1);
      tm.bricks = origins.size();
      t2 = step = Clock::now();
      if (x.bricks == 0) return;  // every candidate lay wholly on one side: an empty mesh
      // 2. each cell's case; triangles, vertices, seam vertices per brick
      detail::classify_cells(x);
      tm.seam_vertices = x.seams;
      mark(&ExtractTimings::classify);
      if (x.triangles == 0) return;
      detail::hash_seam_vertices(x);  // 3. the vertices other bricks look up, by edge hash
      mark(&ExtractTimings::seams);
      detail::sort_seam_vertices(x);  // 4. radix-sorted by hash
      mark(&ExtractTimings::sort);
      // 5-6. the sorted hashes as a lookup table; every brick's vertices and triangles, a
      // neighbour's vertex found there by binary search.
      std::vector<SnapCandidate> near = detail::emit_triangles(x, mesh, mark);
      if (near.empty()) return;
      // 7. vertices close to a voxel moved onto it, and merged
      const SnapReport r = snap_vertices(mesh, std::move(near), f,
                                         kSnapMinArea, options.snap);
      tm.snapped = r.moved;
      tm.merged = r.merged;
      tm.pushed = r.pushed;
      if (timings) {
        tm.snap += ms_since(step);
        step = Clock::now();
      }
    });
  }
  tm.device = ms_since(t2);
  tm.total = ms_since(t0);
  if (timings) *timings = tm;
  return mesh;
}

std::vector<openvdb::Coord> Mesher::surface_bricks(float isovalue, const Options& options) const {
  return state_->index.candidates(make_frame(state_->volume, isovalue, options));
}

Mesh extract(const volume::Volume& v, float isovalue, Device& device, const Options& options, ExtractTimings* timings) {
  const auto t0 = Clock::now();
  Mesher mesher(v, device);
  const double prepare = ms_since(t0);
  Mesh mesh = mesher.extract(isovalue, options, timings);
  if (timings) {
    timings->prepare = prepare;
    timings->total += prepare;
  }
  return mesh;
}

}  // namespace isocurv::mc
