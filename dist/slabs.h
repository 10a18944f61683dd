#pragma once
// How a distributed extraction divides the volume: slabs along index z (the slowest axis of raw,
// NRRD, NIfTI and MetaImage files, so a slab is one contiguous run of the file), cut between
// 8-cell brick layers and balanced by the bricks that carry surface, not by volume: a CT with
// much air, or a sparse .vdb, gives each rank the same share of the real work.
// Tested in tests/dist/test_distributed.cpp.
#include <climits>
#include <cstdint>
#include <vector>

namespace isocurv::dist {

/// Cells (index z) a piece extracts beyond its slab on each side, so that snapping (mc/snap_vertices.h)
/// and the ring of ghost triangles see what the whole extraction sees there: a snapped vertex
/// depends on the cells around its voxel and their neighbours' (two cells), the ghost ring on one
/// more.
constexpr int kExtractGhostCells = 4;

/// Which rank owns which cells: slab r holds the cells whose index z lies in
/// [cuts[r], cuts[r+1]); cuts[0] and cuts.back() are open (INT_MIN, INT_MAX).
struct Slabs {
  std::vector<int> cuts;     ///< ranks + 1 entries, non-decreasing
  int key_origin_z = 0;      ///< the whole extraction's key origin (mc::Frame::key_origin.z)

  int ranks() const { return int(cuts.size()) - 1; }
  /// The rank whose slab holds cell z `z`.
  int owner_of_cell(int z) const;
  /// The rank owning the edge with key `key` (mc/edge_key.h): the slab of its lower end's z.
  int owner_of_key(std::uint64_t key) const;
  /// The cells rank `r` extracts: its slab grown by `margin` on both sides, as an inclusive
  /// [first, last] pair of index z (clamped to the int range).
  std::pair<int, int> extract_range(int r, int margin) const;
};

/// The bricks that carry surface, per brick layer: what balance_slabs divides.
struct LayerBricks {
  int first_layer_z = 0;              ///< index z of the first layer's lowest cell (a multiple of 8)
  std::vector<std::uint64_t> counts;  ///< bricks per layer, from first_layer_z up
};

/// Counts the brick origins' index z `brick_z` by brick layer of the cells [cells_min_z,
/// cells_max_z] (index z; no layers when cells_min_z > cells_max_z), keeping only those within
/// [count_from, count_to] (a rank's even share of the file, when each counts its own).
LayerBricks count_layer_bricks(int cells_min_z, int cells_max_z, const std::vector<int>& brick_z,
                               int count_from = INT_MIN, int count_to = INT_MAX);

/// What a layer costs a rank that reads its slab in part (volume::LoadOptions::z_slab), in tenths
/// of a microsecond: its surface bricks (the extraction), its 8^3 blocks (reading the slices,
/// whatever they hold) and, among those, the blocks that are not constant (each built into a grid
/// leaf). Measured here (`isocurv extract --json`, PoCL on 2 cores): a 384^3 CT-like uint16 ball,
/// every block a leaf, loads at 7.8 us a block; the 512^3 octa-flower (uint8, mostly constant
/// air) at 2 us a block; extraction costs about 12 us a surface brick. On a dense scan reading
/// outweighs extracting by ten, so a balance by surface alone gave the ranks holding the air above
/// and below a ball 1.3x an even share of slices to read and hold.
inline constexpr std::uint64_t kSurfaceBrickCost = 120, kBlockReadCost = 20, kLeafBuildCost = 58;

/// The layers' costs for a read in part: surface_bricks * kSurfaceBrickCost + blocks_per_layer *
/// kBlockReadCost + leaves * kLeafBuildCost each (`leaves` as long as `surface_bricks`).
std::vector<std::uint64_t> read_in_part_costs(const std::vector<std::uint64_t>& surface_bricks,
                                              const std::vector<std::uint64_t>& leaves,
                                              std::uint64_t blocks_per_layer);

/// Splits the brick layers `first_layer_z`, +8, ... (index z of each layer's lowest cell) among
/// `ranks` so that the surface bricks (or costs) `layer_bricks[i]` of each layer add up as evenly as
/// whole layers allow (each cut where the running total first reaches r/ranks of the whole).
/// Ranks may get no layer when there are fewer layers with surface than ranks.
/// Deterministic: every rank computes the same slabs from the same counts.
Slabs balance_slabs(const std::vector<std::uint64_t>& layer_bricks, int first_layer_z, int ranks,
                    int key_origin_z);

}  // namespace isocurv::dist
