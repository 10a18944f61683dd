#include "mc/detail/mesher_passes.h"

#include <algorithm>
#include <cstddef>

#include "core/cl_input.h"
#include "core/cl_launch.h"
#include "core/cl_radix_sort.h"
#include "core/cl_scan.h"
#include "core/cl_scratch.h"
#include "core/error.h"
#include "core/huge_pages.h"
#include "mc/case_table.h"
#include "mc/edge_key.h"

namespace isocurv::kernels {
extern const char* const marching_cubes_cl;
extern const char* const mc_layout_h;
}

namespace isocurv::mc::detail {

// The C header's layout as the host sees it (mc_emit reads McEmitParams from one buffer).
static_assert(sizeof(McEmitParams) == 40 * 4, "McEmitParams: 40 packed 4-byte fields");
static_assert(offsetof(McEmitParams, hash_blocks) == 12 * 4);
static_assert(offsetof(McEmitParams, world) == 16 * 4);
static_assert(offsetof(McEmitParams, bricks) == 32 * 4);
static_assert(offsetof(McEmitParams, snap_capacity) == 39 * 4);
static_assert(APRON == kApron && BRICK_SAMPLES == kBrickSamples, "mc/bricks.h's brick layout");
namespace {

constexpr std::size_t kBricksPerGroup = 1;  // one work item per brick (PoCL runs a group on one thread)
constexpr std::size_t kTableGroup = 64;

cl_int4 to_int4(const openvdb::Coord& c) { return cl_int4{{c.x(), c.y(), c.z(), 0}}; }

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

MesherTables::MesherTables(Device& device) {
  static const std::string source = std::string(kernels::mc_layout_h) + "\n" + kernels::marching_cubes_cl;
  program = &device.program("marching_cubes", source.c_str());
  const CaseTable& t = case_table();
  tri_count = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::size_t(256),
                         static_cast<void*>(const_cast<std::uint8_t*>(t.triangle_count.data())));
  tri_edges = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, std::size_t(256 * 16),
                         static_cast<void*>(const_cast<std::int8_t*>(&t.edges[0][0])));
  crossed = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(t.crossed),
                       static_cast<void*>(const_cast<std::uint16_t*>(t.crossed.data())));
  case_slots = cl::Buffer(device.context(), CL_MEM_READ_WRITE, 256 * 16 * sizeof(cl_ushort));
  cl::Kernel& slots = device.kernel(*program, "mc_case_slots");
  set_args(slots, tri_edges, case_slots);
  launch(device.queue(), slots, 256, kTableGroup);
}

void gather_samples(Extraction& x, const BrickIndex& index, std::vector<openvdb::Coord>& origins) {
  cl::CommandQueue& q = x.device.queue();
  ScratchBuffers& scratch = x.device.scratch();
  // Gather straight into the device buffer (mapped: zero-copy on CPU devices).
  const std::size_t sample_bytes = origins.size() * kBrickSamples * sizeof(float);
  x.samples = &scratch.get(kMcSamples, sample_bytes);
  auto* mapped =
      static_cast<float*>(q.enqueueMapBuffer(*x.samples, CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION, 0, sample_bytes));
  try {
    index.gather(x.frame, origins, mapped);
  } catch (...) {
    q.enqueueUnmapMemObject(*x.samples, mapped);
    throw;
  }
  q.enqueueUnmapMemObject(*x.samples, mapped);
  // At most 5 triangles a cell: the per-brick counts and their 32-bit scans cannot wrap.
  if (origins.size() > 0xffffffffULL / (5 * 512))
    throw Error(x.path, "isosurface too large (" + std::to_string(origins.size()) + " bricks)");
  x.bricks = static_cast<std::uint32_t>(origins.size());
  std::vector<cl_int4> orig4(origins.size());
  for (std::size_t i = 0; i < origins.size(); ++i) orig4[i] = to_int4(origins[i]);
  x.origins = &scratch.get(kMcOrigins, std::max<std::size_t>(orig4.size(), 1) * sizeof(cl_int4));
  if (!orig4.empty()) q.enqueueWriteBuffer(*x.origins, CL_TRUE, 0, orig4.size() * sizeof(cl_int4), orig4.data());
}

void classify_cells(Extraction& x) {
  cl::CommandQueue& q = x.device.queue();
  ScratchBuffers& scratch = x.device.scratch();
  const std::uint32_t n = x.bricks;
  x.cases = &scratch.get(kMcCases, std::size_t(n) * 512);
  x.row_ranks = &scratch.get(kMcRowRanks, std::size_t(n) * 64 * sizeof(cl_ushort));
  x.triangle_offsets = &scratch.get(kMcTriangleOffsets, n * sizeof(std::uint32_t));
  x.vertex_offsets = &scratch.get(kMcVertexOffsets, n * sizeof(std::uint32_t));
  x.seam_offsets = &scratch.get(kMcSeamOffsets, n * sizeof(std::uint32_t));
  cl::Kernel& classify = x.device.kernel(*x.tables.program, "mc_classify");
  set_args(classify, *x.samples, *x.origins, n, to_int4(x.frame.cells.min()), to_int4(x.frame.cells.max()),
           x.tables.tri_count, x.tables.crossed, *x.cases, *x.row_ranks, *x.triangle_offsets, *x.vertex_offsets,
           *x.seam_offsets);
  launch(q, classify, n, kBricksPerGroup);
  cl::Buffer& counts = scratch.get(kMcCounts, 3 * sizeof(std::uint32_t));
  enqueue_exclusive_scan(x.device, *x.triangle_offsets, *x.triangle_offsets, n, &counts, 0);
  enqueue_exclusive_scan(x.device, *x.vertex_offsets, *x.vertex_offsets, n, &counts, 1);
  enqueue_exclusive_scan(x.device, *x.seam_offsets, *x.seam_offsets, n, &counts, 2);
  std::uint32_t total[3];
  q.enqueueReadBuffer(counts, CL_TRUE, 0, sizeof total, total);
  x.triangles = total[0], x.vertices = total[1], x.seams = total[2];
  if (std::uint64_t(x.triangles) * 3 >= 0xffffffffULL)
    throw Error(x.path, "isosurface too large (over 1.4 billion triangles)");
}

void hash_seam_vertices(Extraction& x) {
  ScratchBuffers& scratch = x.device.scratch();
  const Frame& f = x.frame;
  // Hash coordinates count from the brick-aligned corner below the cells (edge_hash).
  const openvdb::Coord origin(f.cells.min().x() & ~7, f.cells.min().y() & ~7, f.cells.min().z() & ~7);
  const openvdb::Coord span = f.cells.max() + openvdb::Coord(1) - origin;  // largest coordinate
  x.hash_origin = to_int4(origin);
  x.hash_blocks = cl_uint2{{cl_uint(span.z() / 8 + 1), cl_uint(span.y() / 8 + 1)}};
  x.hash_mask = hash_mask(x.options.hash_bits);
  // Every hash lies below 2^range_bits: the sort needs no more key bits than that.
  const std::uint64_t blocks = std::uint64_t(x.hash_blocks.s[0]) * x.hash_blocks.s[1] * std::uint64_t(span.x() / 8 + 1);
  const std::uint64_t range = std::min(blocks * kEdgeSlotsPerBlock, std::uint64_t(x.hash_mask) + 1);
  x.range_bits = 1;
  while (x.range_bits < 32 && (std::uint64_t(1) << x.range_bits) < range) ++x.range_bits;
  const std::size_t room = std::max<std::uint32_t>(x.seams, 1);
  x.hashes = &scratch.get(kMcHashes, room * sizeof(std::uint32_t));
  x.order = &scratch.get(kMcOrder, room * sizeof(std::uint32_t));
  x.seam_vertices = &scratch.get(kMcSeamVertices, room * sizeof(std::uint32_t));
  x.seam_keys = &scratch.get(kMcSeamKeys, room * sizeof(cl_ulong));
  cl::Kernel& seams = x.device.kernel(*x.tables.program, "mc_seams");
  set_args(seams, *x.origins, x.bricks, to_int4(f.cells.max()), to_int4(f.key_origin), x.hash_origin, x.hash_blocks,
           x.hash_mask, x.tables.crossed, *x.cases, *x.row_ranks, *x.vertex_offsets, *x.seam_offsets, *x.hashes,
           *x.order, *x.seam_vertices, *x.seam_keys);
  launch(x.device.queue(), seams, x.bricks, kBricksPerGroup);
}

void sort_seam_vertices(Extraction& x) {
  enqueue_radix_sort_pairs(x.device, *x.hashes, *x.order, x.seams, x.range_bits);
}

void build_seam_table(Extraction& x) {
  ScratchBuffers& scratch = x.device.scratch();
  int table_bits = 1;
  while (table_bits < x.range_bits && (std::uint64_t(1) << table_bits) <= x.seams) ++table_bits;
  table_bits = std::min(table_bits, 24);
  x.shift = static_cast<cl_uint>(x.range_bits - table_bits);
  x.buckets = 1u << table_bits;
  const std::size_t room = std::max<std::uint32_t>(x.seams, 1);
  x.table_hashes = &scratch.get(kMcTableHashes, room * sizeof(std::uint32_t));
  x.table_vertices = &scratch.get(kMcTableVertices, room * sizeof(std::uint32_t));
  x.table_keys = &scratch.get(kMcTableKeys, room * sizeof(cl_ulong));
  x.bucket_starts = &scratch.get(kMcBucketStarts, (std::size_t(x.buckets) + 1) * sizeof(std::uint32_t));
  cl::Kernel& table = x.device.kernel(*x.tables.program, "mc_table");
  set_args(table, *x.hashes, *x.order, *x.seam_vertices, *x.seam_keys, x.seams, x.shift, x.buckets, *x.table_hashes,
           *x.table_vertices, *x.table_keys, *x.bucket_starts);
  launch(x.device.queue(), table, std::size_t(x.seams) + 1, kTableGroup);
}

std::vector<SnapCandidate> emit_triangles(Extraction& x, Mesh& mesh, const Mark& mark) {
  cl::CommandQueue& q = x.device.queue();
  ScratchBuffers& scratch = x.device.scratch();
  // Positions and triangles (and edge keys when asked for), straight into the mesh.
  resize_in_huge_pages(mesh.positions, x.vertices);
  resize_in_huge_pages(mesh.triangles, x.triangles);
  const cl_uint write_keys = x.options.keep_edge_keys ? 1 : 0;
  if (write_keys) resize_in_huge_pages(mesh.edge_keys, x.vertices);
  OutputArray out_pos(x.device, mesh.positions, kMcPositions);
  OutputArray out_tris(x.device, mesh.triangles, kMcTriangles);
  OutputArray out_keys(x.device, mesh.edge_keys, kMcKeys);
  mark(&ExtractTimings::read);

  build_seam_table(x);
  // The vertices near a voxel (Options::snap), listed in any order: at most one entry each.
  const bool snapping = x.options.snap > 0;
  const std::size_t snap_room = snapping ? x.vertices : 1;
  cl::Buffer& snap_count = scratch.get(kMcSnapCount, sizeof(cl_uint));
  cl::Buffer& snap_edges = scratch.get(kMcSnapEdges, snap_room * sizeof(cl_ulong));
  cl::Buffer& snap_vertices = scratch.get(kMcSnapVertices, snap_room * sizeof(cl_uint));
  static const cl_uint zero = 0;  // read by a queued copy
  if (snapping) q.enqueueWriteBuffer(snap_count, CL_FALSE, 0, sizeof zero, &zero);
  McEmitParams& p = x.emit_params;  // read by the queued copy: lives in x
  p = McEmitParams{};
  const openvdb::Coord cell_max = x.frame.cells.max();
  for (int a = 0; a < 3; ++a) {
    p.cell_max[a] = cell_max[a];
    p.key_origin[a] = x.frame.key_origin[a];
    p.hash_origin[a] = x.hash_origin.s[a];
  }
  p.hash_blocks[0] = x.hash_blocks.s[0], p.hash_blocks[1] = x.hash_blocks.s[1];
  p.hash_mask = x.hash_mask;
  p.min_fraction = kMinEdgeFraction;
  for (int i = 0; i < 12; ++i) p.world[i] = x.frame.world[i];
  p.bricks = x.bricks, p.triangles = x.triangles, p.vertices = x.vertices, p.seams = x.seams;
  p.shift = x.shift;
  p.write_keys = write_keys;
  p.snap = x.options.snap;
  p.snap_capacity = static_cast<cl_uint>(snap_room);
  cl::Buffer& params = scratch.get(kMcEmitParams, sizeof(McEmitParams));
  q.enqueueWriteBuffer(params, CL_FALSE, 0, sizeof(McEmitParams), &p);
  cl::Kernel& emit = x.device.kernel(*x.tables.program, "mc_emit");
  set_args(emit, *x.samples, *x.origins, params, x.tables.case_slots, x.tables.tri_count,
           x.tables.crossed, *x.cases, *x.triangle_offsets, *x.vertex_offsets, *x.table_hashes,
           *x.table_vertices, *x.table_keys, *x.bucket_starts, out_pos.buffer(), out_tris.buffer(),
           out_keys.buffer(), snap_count, snap_edges, snap_vertices);
  launch(q, emit, x.bricks, kBricksPerGroup);
  mark(&ExtractTimings::emit);

  out_pos.fetch(q);
  out_tris.fetch(q);
  out_keys.fetch(q);
  cl_uint nsnap = 0;
  if (snapping) q.enqueueReadBuffer(snap_count, CL_FALSE, 0, sizeof nsnap, &nsnap);
  q.finish();
  mark(&ExtractTimings::read);
  std::vector<SnapCandidate> candidates;
  if (nsnap == 0) return candidates;
  nsnap = std::min<cl_uint>(nsnap, static_cast<cl_uint>(x.vertices));
  std::vector<cl_ulong> edges(nsnap);
  std::vector<cl_uint> vertices(nsnap);
  q.enqueueReadBuffer(snap_edges, CL_FALSE, 0, nsnap * sizeof(cl_ulong), edges.data());
  q.enqueueReadBuffer(snap_vertices, CL_TRUE, 0, nsnap * sizeof(cl_uint), vertices.data());
  candidates.resize(nsnap);
  for (std::size_t i = 0; i < nsnap; ++i) candidates[i] = {edges[i], vertices[i]};
  return candidates;
}

}  // namespace isocurv::mc::detail
