#include "mc/extract.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "core/cl_input.h"
#include "core/cl_launch.h"
#include "core/cl_radix_sort.h"
#include "core/cl_scan.h"
#include "core/cl_scratch.h"
#include "core/error.h"
#include "core/huge_pages.h"
#include "mc/bricks.h"
#include "mc/case_table.h"
#include "mc/edge_key.h"
#include "mc/frame.h"
#include "mc/snap_vertices.h"
#include "mc/triangle_quality.h"

namespace isocurv::kernels {
extern const char* const marching_cubes_cl;
}

namespace isocurv::mc {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

constexpr std::size_t kBricksPerGroup = 1;  // one work item per brick (PoCL runs a group on one thread)
constexpr std::size_t kTableGroup = 64;

cl_int4 to_int4(const openvdb::Coord& c) { return cl_int4{{c.x(), c.y(), c.z(), 0}}; }

// Waits for queued work (kernels may be writing into the mesh's vectors) before an error unwinds
// them; a second failure there changes nothing for the caller.
void drain(cl::CommandQueue& q) {
  try {
    q.finish();
  } catch (...) {
  }
}

// A kernel's output that ends in a host vector (already sized). On CPU devices the kernel writes
// the vector's memory itself (a CL_MEM_USE_HOST_PTR buffer: PoCL uses the pointer as is, and
// mapping it afterwards is the synchronisation, without a copy); elsewhere it writes a device
// scratch buffer that fetch() reads back. An empty vector gets a small scratch buffer (an unused
// kernel argument).
template <class T>
class OutputArray {
 public:
  template <class A>
  OutputArray(Device& device, std::vector<T, A>& v, std::size_t scratch_slot)
      : data_(v.data()), bytes_(v.size() * sizeof(T)) {
    if (bytes_ > 0 && works_in_host_memory(device)) {
      own_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_USE_HOST_PTR, bytes_, data_);
      buffer_ = &own_;
    } else {
      buffer_ = &device.scratch().get(scratch_slot, std::max<std::size_t>(bytes_, sizeof(T)));
    }
  }
  OutputArray(const OutputArray&) = delete;  // buffer_ may point at own_
  OutputArray& operator=(const OutputArray&) = delete;
  cl::Buffer& buffer() { return *buffer_; }
  /// Enqueues what brings the kernel's results into the vector (blocks for a mapped buffer).
  void fetch(cl::CommandQueue& q) {
    if (bytes_ == 0) return;
    if (buffer_ == &own_) {
      void* p = q.enqueueMapBuffer(own_, CL_TRUE, CL_MAP_READ, 0, bytes_);
      q.enqueueUnmapMemObject(own_, p);
    } else {
      q.enqueueReadBuffer(*buffer_, CL_FALSE, 0, bytes_, data_);
    }
  }

 private:
  void* data_;
  std::size_t bytes_;
  cl::Buffer own_;
  cl::Buffer* buffer_ = nullptr;
};

template <class T, class A>
OutputArray(Device&, std::vector<T, A>&, std::size_t) -> OutputArray<T>;

}  // namespace

struct Mesher::State {
  const volume::Volume& volume;
  Device& device;
  BrickIndex index;
  cl::Program* program = nullptr;
  cl::Buffer tri_count, tri_edges, crossed, case_slots;
  State(const volume::Volume& v, Device& d) : volume(v), device(d), index(v) {}
};

Mesher::Mesher(const volume::Volume& v, Device& device) : state_(std::make_unique<State>(v, device)) {
  State& s = *state_;
  s.program = &device.program("marching_cubes", kernels::marching_cubes_cl);
  const CaseTable& t = case_table();
  s.tri_count = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::size_t(256),
                           static_cast<void*>(const_cast<std::uint8_t*>(t.triangle_count.data())));
  s.tri_edges = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::size_t(256 * 16),
                           static_cast<void*>(const_cast<std::int8_t*>(&t.edges[0][0])));
  s.crossed = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(t.crossed),
                         static_cast<void*>(const_cast<std::uint16_t*>(t.crossed.data())));
  s.case_slots = cl::Buffer(device.context(), CL_MEM_READ_WRITE, 256 * 16 * sizeof(cl_ushort));
  try {
    cl::Kernel& slots = device.kernel(*s.program, "mc_case_slots");
    set_args(slots, s.tri_edges, s.case_slots);
    launch(device.queue(), slots, 256, kTableGroup);
  } catch (const cl::Error& e) {
    drain(device.queue());
    throw Error(std::string("marching cubes setup failed on the OpenCL device: ") + e.what() + " (" +
                cl_error_name(e.err()) + ")");
  }
}

Mesher::~Mesher() = default;

Mesh Mesher::extract(float isovalue, const Options& options, ExtractTimings* timings) {
  State& st = *state_;
  ExtractTimings tm;
  const auto t0 = Clock::now();
  const Frame f = make_frame(st.volume, isovalue, options);
  std::vector<openvdb::Coord> origins = st.index.candidates(f);
  tm.select = ms_since(t0);
  auto t1 = Clock::now();
  Mesh mesh;
  auto t2 = t1;
  auto step = t2;
  // With timings requested, drain the queue after each step and charge it its wall time.
  auto mark = [&](double ExtractTimings::*field) {
    if (!timings) return;
    st.device.queue().finish();
    tm.*field += ms_since(step);
    step = Clock::now();
  };
  if (!origins.empty()) {
    try {
      auto& q = st.device.queue();
      ScratchBuffers& scratch = st.device.scratch();
      // Gather straight into the device buffer (mapped: zero-copy on CPU devices).
      const std::size_t sample_bytes = origins.size() * kBrickSamples * sizeof(float);
      cl::Buffer& d_samples = scratch.get(kMcSamples, sample_bytes);
      auto* mapped = static_cast<float*>(q.enqueueMapBuffer(d_samples, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, sample_bytes));
      try {
        st.index.gather(f, origins, mapped);
      } catch (...) {
        q.enqueueUnmapMemObject(d_samples, mapped);
        throw;
      }
      q.enqueueUnmapMemObject(d_samples, mapped);
      tm.gather = ms_since(t1);
      tm.bricks = origins.size();
      t2 = step = Clock::now();
      if (!origins.empty()) {  // else every candidate lay wholly on one side: an empty mesh
        // At most 5 triangles a cell: the per-brick counts and their 32-bit scans cannot wrap.
        if (origins.size() > 0xffffffffULL / (5 * 512))
          throw Error(st.volume.path, "isosurface too large (" + std::to_string(origins.size()) + " bricks)");
        const auto nbricks = static_cast<std::uint32_t>(origins.size());
        std::vector<cl_int4> orig4(origins.size());
        for (std::size_t i = 0; i < origins.size(); ++i) orig4[i] = to_int4(origins[i]);
        cl::Buffer& d_origins = scratch.get(kMcOrigins, orig4.size() * sizeof(cl_int4));
        q.enqueueWriteBuffer(d_origins, CL_FALSE, 0, orig4.size() * sizeof(cl_int4), orig4.data());
        // Every cell's case; triangles, vertices and seam vertices per brick, each scanned in
        // place into the brick's first one.
        cl::Buffer& d_cases = scratch.get(kMcCases, std::size_t(nbricks) * 512);
        cl::Buffer& d_row_ranks = scratch.get(kMcRowRanks, std::size_t(nbricks) * 64 * sizeof(cl_ushort));
        cl::Buffer& d_tri_offsets = scratch.get(kMcTriangleOffsets, nbricks * sizeof(std::uint32_t));
        cl::Buffer& d_vert_offsets = scratch.get(kMcVertexOffsets, nbricks * sizeof(std::uint32_t));
        cl::Buffer& d_seam_offsets = scratch.get(kMcSeamOffsets, nbricks * sizeof(std::uint32_t));
        const cl_int4 cmin = to_int4(f.cells.min()), cmax = to_int4(f.cells.max()), korg = to_int4(f.key_origin);

        cl::Kernel& classify = st.device.kernel(*st.program, "mc_classify");
        set_args(classify, d_samples, d_origins, nbricks, cmin, cmax, st.tri_count, st.crossed, d_cases,
                 d_row_ranks, d_tri_offsets, d_vert_offsets, d_seam_offsets);
        launch(q, classify, nbricks, kBricksPerGroup);
        cl::Buffer& d_counts = scratch.get(kMcCounts, 3 * sizeof(std::uint32_t));
        enqueue_exclusive_scan(st.device, d_tri_offsets, d_tri_offsets, nbricks, &d_counts, 0);
        enqueue_exclusive_scan(st.device, d_vert_offsets, d_vert_offsets, nbricks, &d_counts, 1);
        enqueue_exclusive_scan(st.device, d_seam_offsets, d_seam_offsets, nbricks, &d_counts, 2);
        std::uint32_t counts[3];
        q.enqueueReadBuffer(d_counts, CL_TRUE, 0, sizeof counts, counts);
        const std::uint32_t ntri = counts[0], nvert = counts[1], nseam = counts[2];
        tm.seam_vertices = nseam;
        mark(&ExtractTimings::classify);
        if (std::uint64_t(ntri) * 3 >= 0xffffffffULL)
          throw Error(st.volume.path, "isosurface too large (over 1.4 billion triangles)");
        if (ntri > 0) {
          // Hash coordinates count from the brick-aligned corner below the cells (edge_hash).
          const openvdb::Coord hash_origin(f.cells.min().x() & ~7, f.cells.min().y() & ~7, f.cells.min().z() & ~7);
          const openvdb::Coord hash_span = f.cells.max() + openvdb::Coord(1) - hash_origin;  // largest coordinate
          const cl_uint2 blocks{{cl_uint(hash_span.z() / 8 + 1), cl_uint(hash_span.y() / 8 + 1)}};
          const cl_int4 horg = to_int4(hash_origin);
          const cl_uint mask = hash_mask(options.hash_bits);
          // The seam vertices as (hash, j) pairs, sorted by hash.
          const std::size_t nseam1 = std::max<std::uint32_t>(nseam, 1);
          cl::Buffer& d_hash = scratch.get(kMcHashes, nseam1 * sizeof(std::uint32_t));
          cl::Buffer& d_order = scratch.get(kMcOrder, nseam1 * sizeof(std::uint32_t));
          cl::Buffer& d_seam_vertex = scratch.get(kMcSeamVertices, nseam1 * sizeof(std::uint32_t));
          cl::Buffer& d_seam_keys = scratch.get(kMcSeamKeys, nseam1 * sizeof(cl_ulong));
          cl::Kernel& seams = st.device.kernel(*st.program, "mc_seams");
          set_args(seams, d_origins, nbricks, cmax, korg, horg, blocks, mask, st.crossed, d_cases, d_row_ranks,
                   d_vert_offsets, d_seam_offsets, d_hash, d_order, d_seam_vertex, d_seam_keys);
          launch(q, seams, nbricks, kBricksPerGroup);
          mark(&ExtractTimings::seams);

          // Every hash lies below 2^range_bits: the sort needs no more key bits than that.
          const std::uint64_t nblocks = std::uint64_t(blocks.s[0]) * blocks.s[1] * std::uint64_t(hash_span.x() / 8 + 1);
          const std::uint64_t hash_range = std::min(nblocks * kEdgeSlotsPerBlock, std::uint64_t(mask) + 1);
          int range_bits = 1, table_bits = 1;
          while (range_bits < 32 && (std::uint64_t(1) << range_bits) < hash_range) ++range_bits;
          enqueue_radix_sort_pairs(st.device, d_hash, d_order, nseam, range_bits);
          mark(&ExtractTimings::sort);

          // The lookup table, with a bucket index over the top bits of the hashes' range (about
          // one seam vertex a bucket).
          while (table_bits < range_bits && (std::uint64_t(1) << table_bits) <= nseam) ++table_bits;
          table_bits = std::min(table_bits, 24);
          const cl_uint shift = static_cast<cl_uint>(range_bits - table_bits);
          const cl_uint nbuckets = 1u << table_bits;
          cl::Buffer& d_table_hashes = scratch.get(kMcTableHashes, nseam1 * sizeof(std::uint32_t));
          cl::Buffer& d_table_vertices = scratch.get(kMcTableVertices, nseam1 * sizeof(std::uint32_t));
          cl::Buffer& d_table_keys = scratch.get(kMcTableKeys, nseam1 * sizeof(cl_ulong));
          cl::Buffer& d_starts = scratch.get(kMcBucketStarts, (std::size_t(nbuckets) + 1) * sizeof(std::uint32_t));

          // Positions and triangles (and edge keys when asked for), straight into the mesh.
          resize_in_huge_pages(mesh.positions, nvert);
          resize_in_huge_pages(mesh.triangles, ntri);
          const cl_uint write_keys = options.keep_edge_keys ? 1 : 0;
          if (write_keys) resize_in_huge_pages(mesh.edge_keys, nvert);
          OutputArray out_pos(st.device, mesh.positions, kMcPositions);
          OutputArray out_tris(st.device, mesh.triangles, kMcTriangles);
          OutputArray out_keys(st.device, mesh.edge_keys, kMcKeys);
          mark(&ExtractTimings::read);

          cl::Kernel& table = st.device.kernel(*st.program, "mc_table");
          set_args(table, d_hash, d_order, d_seam_vertex, d_seam_keys, nseam, shift, nbuckets, d_table_hashes,
                   d_table_vertices, d_table_keys, d_starts);
          launch(q, table, std::size_t(nseam) + 1, kTableGroup);
          cl_float16 world{};
          for (int i = 0; i < 12; ++i) world.s[i] = f.world[i];
          // The vertices near a voxel (Options::snap), listed in any order: at most one entry each.
          const bool snapping = options.snap > 0;
          const std::size_t snap_room = snapping ? nvert : 1;
          cl::Buffer& d_snap_count = scratch.get(kMcSnapCount, sizeof(cl_uint));
          cl::Buffer& d_snap_edges = scratch.get(kMcSnapEdges, snap_room * sizeof(cl_ulong));
          cl::Buffer& d_snap_vertices = scratch.get(kMcSnapVertices, snap_room * sizeof(cl_uint));
          const cl_uint zero = 0;
          if (snapping) q.enqueueWriteBuffer(d_snap_count, CL_FALSE, 0, sizeof zero, &zero);
          cl::Kernel& emit = st.device.kernel(*st.program, "mc_emit");
          set_args(emit, d_samples, d_origins, nbricks, cmax, korg, horg, blocks, mask, kMinEdgeFraction, world,
                   st.case_slots, st.tri_count, st.crossed, d_cases, d_tri_offsets, ntri, d_vert_offsets, nvert,
                   d_table_hashes, d_table_vertices, d_table_keys, nseam, d_starts, shift, out_pos.buffer(),
                   out_tris.buffer(), write_keys, out_keys.buffer(), options.snap, d_snap_count,
                   static_cast<cl_uint>(snap_room), d_snap_edges, d_snap_vertices);
          launch(q, emit, nbricks, kBricksPerGroup);
          mark(&ExtractTimings::emit);

          out_pos.fetch(q);
          out_tris.fetch(q);
          out_keys.fetch(q);
          cl_uint nsnap = 0;
          if (snapping) q.enqueueReadBuffer(d_snap_count, CL_FALSE, 0, sizeof nsnap, &nsnap);
          q.finish();
          mark(&ExtractTimings::read);
          if (nsnap > 0) {
            nsnap = std::min<cl_uint>(nsnap, static_cast<cl_uint>(nvert));
            std::vector<cl_ulong> edges(nsnap);
            std::vector<cl_uint> vertices(nsnap);
            q.enqueueReadBuffer(d_snap_edges, CL_FALSE, 0, nsnap * sizeof(cl_ulong), edges.data());
            q.enqueueReadBuffer(d_snap_vertices, CL_TRUE, 0, nsnap * sizeof(cl_uint), vertices.data());
            std::vector<SnapCandidate> candidates(nsnap);
            for (std::size_t i = 0; i < nsnap; ++i) candidates[i] = {edges[i], vertices[i]};
            const SnapReport r = snap_vertices(mesh, std::move(candidates), f, kSnapMinArea * voxel_face_area(st.volume),
                                               options.snap);
            tm.snapped = r.moved;
            tm.merged = r.merged;
            tm.pushed = r.pushed;
            if (timings) {
              tm.snap += ms_since(step);
              step = Clock::now();
            }
          }
        }
      }
    } catch (const cl::Error& e) {
      drain(st.device.queue());
      throw Error(st.volume.path, std::string("marching cubes failed on the OpenCL device: ") + e.what() + " (" +
                                      cl_error_name(e.err()) + ")");
    } catch (...) {
      drain(st.device.queue());
      throw;
    }
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
