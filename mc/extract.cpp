#include "mc/extract.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/cl_radix_sort.h"
#include "core/cl_scan.h"
#include "core/cl_scratch.h"
#include "core/error.h"
#include "core/huge_pages.h"
#include "mc/bricks.h"
#include "mc/case_table.h"
#include "mc/edge_key.h"
#include "mc/frame.h"

namespace isocurv::kernels {
extern const char* const marching_cubes_cl;
}

namespace isocurv::mc {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

cl_int4 to_int4(const openvdb::Coord& c) { return cl_int4{{c.x(), c.y(), c.z(), 0}}; }

template <typename... Args>
void set_args(cl::Kernel& k, const Args&... args) {
  cl_uint i = 0;
  (k.setArg(i++, args), ...);
}

}  // namespace

struct Mesher::State {
  const volume::Volume& volume;
  Device& device;
  BrickIndex index;
  cl::Program* program = nullptr;
  cl::Buffer tri_count, tri_edges;
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
        gather_bricks(st.volume, f, origins, mapped);
      } catch (...) {
        q.enqueueUnmapMemObject(d_samples, mapped);
        throw;
      }
      q.enqueueUnmapMemObject(d_samples, mapped);
      tm.gather = ms_since(t1);
      tm.bricks = origins.size();
      t2 = step = Clock::now();
      if (!origins.empty()) {  // else every candidate lay wholly on one side: an empty mesh
        const auto ncells = static_cast<std::uint32_t>(origins.size() * 512);
        std::vector<cl_int4> orig4(origins.size());
        for (std::size_t i = 0; i < origins.size(); ++i) orig4[i] = to_int4(origins[i]);
        cl::Buffer& d_origins = scratch.get(kMcOrigins, orig4.size() * sizeof(cl_int4));
        q.enqueueWriteBuffer(d_origins, CL_FALSE, 0, orig4.size() * sizeof(cl_int4), orig4.data());
        // Triangles and owned vertices per cell, each scanned in place into the cell's first one.
        cl::Buffer& d_tri_offsets = scratch.get(kMcTriangleOffsets, ncells * sizeof(std::uint32_t));
        cl::Buffer& d_vert_offsets = scratch.get(kMcVertexOffsets, ncells * sizeof(std::uint32_t));
        const cl_int4 cmin = to_int4(f.cells.min()), cmax = to_int4(f.cells.max()), korg = to_int4(f.key_origin);

        cl::Kernel classify(*st.program, "mc_classify");
        set_args(classify, d_samples, d_origins, ncells, cmin, cmax, st.tri_count, d_tri_offsets, d_vert_offsets);
        q.enqueueNDRangeKernel(classify, cl::NullRange, cl::NDRange(ncells));
        const std::uint32_t ntri = exclusive_scan(st.device, d_tri_offsets, d_tri_offsets, ncells);
        const std::uint32_t nvert = exclusive_scan(st.device, d_vert_offsets, d_vert_offsets, ncells);
        mark(&ExtractTimings::classify);
        if (std::uint64_t(ntri) * 3 >= 0xffffffffULL)
          throw Error(st.volume.path, "isosurface too large (over 1.4 billion triangles)");
        if (ntri > 0) {
          cl::Buffer& d_pos = scratch.get(kMcPositions, std::size_t(nvert) * 3 * sizeof(float));
          cl::Buffer& d_keys = scratch.get(kMcKeys, std::size_t(nvert) * sizeof(cl_ulong));
          cl::Buffer& d_hash = scratch.get(kMcHashes, std::size_t(nvert) * sizeof(std::uint32_t));
          cl::Buffer& d_order = scratch.get(kMcOrder, std::size_t(nvert) * sizeof(std::uint32_t));
          cl_float16 world{};
          for (int i = 0; i < 12; ++i) world.s[i] = f.world[i];
          const openvdb::Coord key_span = f.cells.max() - f.key_origin + openvdb::Coord(2);
          const cl_uint2 blocks{{cl_uint(key_span.x() / 8 + 1), cl_uint(key_span.y() / 8 + 1)}};
          const cl_uint mask = hash_mask(options.hash_bits);
          cl::Kernel gen(*st.program, "mc_generate");
          set_args(gen, d_samples, d_origins, ncells, cmax, korg, d_vert_offsets, nvert, kMinEdgeFraction, world,
                   blocks, mask, d_pos, d_keys, d_hash, d_order);
          q.enqueueNDRangeKernel(gen, cl::NullRange, cl::NDRange(ncells));
          mark(&ExtractTimings::generate);

          radix_sort_pairs(st.device, d_hash, d_order, nvert, options.hash_bits);
          mark(&ExtractTimings::sort);

          // The lookup table, with a bucket index over the top bits of the hashes' range (about
          // one vertex a bucket).
          const std::uint64_t nblocks = std::uint64_t(blocks.s[0]) * blocks.s[1] * std::uint64_t(key_span.z() / 8 + 1);
          const std::uint64_t hash_range = std::min(nblocks * kEdgeSlotsPerBlock, std::uint64_t(mask) + 1);
          int range_bits = 1, table_bits = 1;
          while (range_bits < 32 && (std::uint64_t(1) << range_bits) < hash_range) ++range_bits;
          while (table_bits < range_bits && (std::uint64_t(1) << table_bits) <= nvert) ++table_bits;
          table_bits = std::min(table_bits, 24);
          const cl_uint shift = static_cast<cl_uint>(range_bits - table_bits);
          const cl_uint nbuckets = 1u << table_bits;
          cl::Buffer& d_table = scratch.get(kMcTable, std::max<std::size_t>(nvert, 1) * 4 * sizeof(std::uint32_t));
          cl::Buffer& d_starts = scratch.get(kMcBucketStarts, (std::size_t(nbuckets) + 1) * sizeof(std::uint32_t));
          cl::Kernel table(*st.program, "mc_table");
          set_args(table, d_hash, d_order, d_keys, nvert, shift, nbuckets, d_table, d_starts);
          q.enqueueNDRangeKernel(table, cl::NullRange, cl::NDRange(std::size_t(nvert) + 1));
          cl::Buffer& d_tris = scratch.get(kMcTriangles, std::size_t(ntri) * 3 * sizeof(std::uint32_t));
          cl::Kernel index(*st.program, "mc_index");
          set_args(index, d_samples, d_origins, ncells, cmax, korg, blocks, mask, st.tri_edges, d_tri_offsets, ntri,
                   d_vert_offsets, d_table, nvert, d_starts, shift, d_tris);
          q.enqueueNDRangeKernel(index, cl::NullRange, cl::NDRange(ncells));
          mark(&ExtractTimings::fuse);

          resize_in_huge_pages(mesh.positions, nvert);
          resize_in_huge_pages(mesh.triangles, ntri);
          q.enqueueReadBuffer(d_pos, CL_FALSE, 0, std::size_t(nvert) * 3 * sizeof(float), mesh.positions.data());
          q.enqueueReadBuffer(d_tris, CL_FALSE, 0, std::size_t(ntri) * 3 * sizeof(std::uint32_t), mesh.triangles.data());
          if (options.keep_edge_keys) {
            resize_in_huge_pages(mesh.edge_keys, nvert);
            q.enqueueReadBuffer(d_keys, CL_FALSE, 0, std::size_t(nvert) * sizeof(cl_ulong), mesh.edge_keys.data());
          }
          q.finish();
          mark(&ExtractTimings::read);
        }
      }
    } catch (const cl::Error& e) {
      throw Error(st.volume.path, std::string("marching cubes failed on the OpenCL device: ") + e.what() + " (" +
                                      cl_error_name(e.err()) + ")");
    }
  }
  tm.device = ms_since(t2);
  tm.total = ms_since(t0);
  if (timings) *timings = tm;
  return mesh;
}

Mesh extract(const volume::Volume& v, float isovalue, Device& device, const Options& options, ExtractTimings* timings) {
  return Mesher(v, device).extract(isovalue, options, timings);
}

}  // namespace isocurv::mc
