#include "mc/extract.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "core/cl_radix_sort.h"
#include "core/cl_scan.h"
#include "core/cl_scratch.h"
#include "core/error.h"
#include "mc/bricks.h"
#include "mc/case_table.h"
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

struct NoBricks {};  // thrown past the device steps when no brick straddles the isovalue

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
      if (origins.empty()) throw NoBricks{};
      const auto ncells = static_cast<std::uint32_t>(origins.size() * 512);
      std::vector<cl_int4> orig4(origins.size());
      for (std::size_t i = 0; i < origins.size(); ++i) orig4[i] = to_int4(origins[i]);
      cl::Buffer& d_origins = scratch.get(kMcOrigins, orig4.size() * sizeof(cl_int4));
      q.enqueueWriteBuffer(d_origins, CL_FALSE, 0, orig4.size() * sizeof(cl_int4), orig4.data());
      // Triangle counts per cell, scanned in place into each cell's first triangle.
      cl::Buffer& d_offsets = scratch.get(kMcOffsets, ncells * sizeof(std::uint32_t));
      const cl_int4 cmin = to_int4(f.cells.min()), cmax = to_int4(f.cells.max()), korg = to_int4(f.key_origin);

      cl::Kernel classify(*st.program, "mc_classify");
      classify.setArg(0, d_samples); classify.setArg(1, d_origins); classify.setArg(2, ncells);
      classify.setArg(3, cmin); classify.setArg(4, cmax); classify.setArg(5, st.tri_count);
      classify.setArg(6, d_offsets);
      q.enqueueNDRangeKernel(classify, cl::NullRange, cl::NDRange(ncells));
      const std::uint32_t ntri = exclusive_scan(st.device, d_offsets, d_offsets, ncells);
      mark(&ExtractTimings::classify);
      const std::uint64_t nvert64 = std::uint64_t(ntri) * 3;
      if (nvert64 >= 0xffffffffULL) throw Error(st.volume.path, "isosurface too large (over 1.4 billion triangles)");
      const auto n = static_cast<std::uint32_t>(nvert64);
      if (n > 0) {
        cl::Buffer& d_pos = scratch.get(kMcPositions, std::size_t(n) * 3 * sizeof(float));
        cl::Buffer& d_keys = scratch.get(kMcKeys, std::size_t(n) * sizeof(cl_ulong));
        cl::Buffer& d_hash = scratch.get(kMcHashes, std::size_t(n) * sizeof(std::uint32_t));
        cl::Buffer& d_order = scratch.get(kMcOrder, std::size_t(n) * sizeof(std::uint32_t));
        cl_float16 world{};
        for (int i = 0; i < 12; ++i) world.s[i] = f.world[i];
        const cl_uint mask = options.hash_bits >= 32 ? 0xffffffffu : ((1u << options.hash_bits) - 1u);
        cl::Kernel gen(*st.program, "mc_generate");
        int a = 0;
        gen.setArg(a++, d_samples); gen.setArg(a++, d_origins); gen.setArg(a++, ncells);
        gen.setArg(a++, cmin); gen.setArg(a++, cmax); gen.setArg(a++, korg);
        gen.setArg(a++, st.tri_count); gen.setArg(a++, st.tri_edges); gen.setArg(a++, d_offsets);
        gen.setArg(a++, kMinEdgeFraction); gen.setArg(a++, world); gen.setArg(a++, mask);
        gen.setArg(a++, d_pos); gen.setArg(a++, d_keys); gen.setArg(a++, d_hash); gen.setArg(a++, d_order);
        q.enqueueNDRangeKernel(gen, cl::NullRange, cl::NDRange(ncells));
        mark(&ExtractTimings::generate);

        // Sort a copy of the hashes with the vertex indices; the originals stay for lookups.
        cl::Buffer& d_sorted_hash = scratch.get(kMcSortedHashes, std::size_t(n) * sizeof(std::uint32_t));
        q.enqueueCopyBuffer(d_hash, d_sorted_hash, 0, 0, std::size_t(n) * sizeof(std::uint32_t));
        radix_sort_pairs(st.device, d_sorted_hash, d_order, n, options.hash_bits);
        mark(&ExtractTimings::sort);

        cl::Buffer& d_rep = scratch.get(kMcRepresentative, std::size_t(n) * sizeof(std::uint32_t));
        cl::Buffer& d_first = scratch.get(kMcFirst, std::size_t(n) * sizeof(std::uint32_t));
        // A table of where each value of the hash's top (up to 16) bits starts narrows each binary search.
        const int table_bits = std::min(16, options.hash_bits);
        const cl_uint shift = static_cast<cl_uint>(options.hash_bits - table_bits);
        const cl_uint nbuckets = 1u << table_bits;
        cl::Buffer& d_starts = scratch.get(kMcBucketStarts, (std::size_t(nbuckets) + 1) * sizeof(std::uint32_t));
        cl::Kernel starts(*st.program, "mc_bucket_starts");
        starts.setArg(0, d_sorted_hash); starts.setArg(1, n); starts.setArg(2, shift); starts.setArg(3, nbuckets);
        starts.setArg(4, d_starts);
        q.enqueueNDRangeKernel(starts, cl::NullRange, cl::NDRange(std::size_t(n) + 1));
        cl::Kernel fuse(*st.program, "mc_fuse");
        fuse.setArg(0, d_hash); fuse.setArg(1, d_keys); fuse.setArg(2, d_sorted_hash); fuse.setArg(3, d_order);
        fuse.setArg(4, n); fuse.setArg(5, d_starts); fuse.setArg(6, shift); fuse.setArg(7, d_rep); fuse.setArg(8, d_first);
        q.enqueueNDRangeKernel(fuse, cl::NullRange, cl::NDRange(n));
        // d_hash is free now: reuse it for the fused indices.
        const std::uint32_t nfused = exclusive_scan(st.device, d_first, d_hash, n);
        mark(&ExtractTimings::fuse);

        cl::Buffer& d_out_pos = scratch.get(kMcOutPositions, std::size_t(nfused) * 3 * sizeof(float));
        cl::Buffer& d_out_keys = scratch.get(kMcOutKeys, (options.keep_edge_keys ? std::size_t(nfused) : 1) * sizeof(cl_ulong));
        cl::Buffer& d_tris = scratch.get(kMcTriangles, std::size_t(n) * sizeof(std::uint32_t));
        cl::Kernel compact(*st.program, "mc_compact");
        compact.setArg(0, d_pos); compact.setArg(1, d_keys); compact.setArg(2, d_rep); compact.setArg(3, d_first);
        compact.setArg(4, d_hash); compact.setArg(5, n); compact.setArg(6, d_out_pos); compact.setArg(7, d_out_keys);
        compact.setArg(8, cl_uint(options.keep_edge_keys ? 1 : 0)); compact.setArg(9, d_tris);
        q.enqueueNDRangeKernel(compact, cl::NullRange, cl::NDRange(n));

        mesh.positions.resize(nfused);
        mesh.triangles.resize(ntri);
        q.enqueueReadBuffer(d_out_pos, CL_FALSE, 0, std::size_t(nfused) * 3 * sizeof(float), mesh.positions.data());
        q.enqueueReadBuffer(d_tris, CL_FALSE, 0, std::size_t(n) * sizeof(std::uint32_t), mesh.triangles.data());
        if (options.keep_edge_keys) {
          mesh.edge_keys.resize(nfused);
          q.enqueueReadBuffer(d_out_keys, CL_FALSE, 0, std::size_t(nfused) * sizeof(cl_ulong), mesh.edge_keys.data());
        }
        q.finish();
        mark(&ExtractTimings::compact);
      }
    } catch (const NoBricks&) {
      // every candidate brick lay wholly on one side: an empty mesh
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
