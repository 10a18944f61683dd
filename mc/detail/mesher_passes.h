#pragma once
// The device mesher's passes (Mesher::extract, mc/extract.cpp, is their driver), in the order of
// the fused marching cubes: the bricks' samples go to the device; each cell's case is classified
// and every brick counts its triangles, vertices and seam vertices (those other bricks look up),
// scanned into offsets; the seam vertices are hashed and radix-sorted by hash into a lookup table;
// then each brick emits its vertices and triangles, finding a neighbour's vertex on a shared edge
// by binary search in that table (vertex fusion without a global hash map). The kernels are in
// mc/marching_cubes.cl; each pass here sets one kernel's arguments from the Extraction.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "mc/detail/mc_layout.h"
#include "mc/bricks.h"
#include "mc/extract.h"
#include "mc/frame.h"
#include "mc/options.h"
#include "mc/snap_vertices.h"

namespace isocurv::mc::detail {

/// What a Mesher keeps on its device between extractions: the program and the case tables.
struct MesherTables {
  cl::Program* program = nullptr;
  cl::Buffer tri_count, tri_edges, crossed, case_slots;
  /// Uploads the case tables and derives the per-case edge slots (mc_case_slots).
  explicit MesherTables(Device& device);
};

/// One extraction between passes: its inputs, then what each pass leaves for the next (device
/// buffers are the device's scratch buffers, valid until its next extraction).
struct Extraction {
  Device& device;
  const MesherTables& tables;
  const Frame& frame;
  const Options& options;
  std::string path;  ///< the volume's, for errors

  // gather_samples
  std::uint32_t bricks = 0;
  cl::Buffer* samples = nullptr;  ///< kBrickSamples per brick
  cl::Buffer* origins = nullptr;  ///< the bricks' origins (int4)
  // classify_cells
  cl::Buffer *cases = nullptr, *row_ranks = nullptr;
  cl::Buffer *triangle_offsets = nullptr, *vertex_offsets = nullptr, *seam_offsets = nullptr;
  std::uint32_t triangles = 0, vertices = 0, seams = 0;
  // hash_seam_vertices
  cl_int4 hash_origin{};
  cl_uint2 hash_blocks{};
  cl_uint hash_mask = 0;
  int range_bits = 1;
  cl::Buffer *hashes = nullptr, *order = nullptr, *seam_vertices = nullptr, *seam_keys = nullptr;
  // build_seam_table
  cl_uint shift = 0, buckets = 0;
  cl::Buffer *table_hashes = nullptr, *table_vertices = nullptr, *table_keys = nullptr, *bucket_starts = nullptr;
  // emit_triangles
  McEmitParams emit_params{};  ///< mc_emit's parameter block (mc/detail/mc_layout.h)
};

/// Pass 1: the samples of the bricks `origins` (BrickIndex::candidates) with their aprons,
/// gathered straight into a device buffer; bricks that turn out not to straddle are dropped from
/// `origins`. Sets bricks, samples, origins.
void gather_samples(Extraction& x, const BrickIndex& index, std::vector<openvdb::Coord>& origins);

/// Pass 2: each cell's case (mc_classify) and, per brick, its triangles, vertices and seam
/// vertices, each scanned into the brick's first. Sets the offsets and the three totals.
/// @throw Error when the counts could wrap their 32-bit scans.
void classify_cells(Extraction& x);

/// Pass 3: the seam vertices as (edge hash, index) pairs with their edge keys and vertex numbers
/// (mc_seams). Sets the hash frame and buffers.
void hash_seam_vertices(Extraction& x);

/// Pass 4: the pairs radix-sorted by hash, on only as many bits as the hashes span.
void sort_seam_vertices(Extraction& x);

/// Pass 5 (enqueued by emit_triangles, once the mesh's arrays exist): the sorted pairs as a
/// lookup table with a bucket index over the hashes' top bits (about one seam vertex a bucket;
/// mc_table).
void build_seam_table(Extraction& x);

/// With timings asked for, drains the queue and charges the time since the last mark to a field.
using Mark = std::function<void(double ExtractTimings::*)>;

/// Pass 6: every brick's vertices and triangles (mc_emit), a vertex on an edge another brick owns
/// found in the table, written into `mesh` (positions, triangles, and edge keys when
/// Options::keep_edge_keys); `mesh` is sized here (charged to `read`, as is reading it back; the
/// table and the kernel to `emit`). Returns the vertices near a voxel that snapping (pass 7,
/// snap_vertices) may move (none unless Options::snap).
std::vector<SnapCandidate> emit_triangles(Extraction& x, Mesh& mesh, const Mark& mark);

}  // namespace isocurv::mc::detail
