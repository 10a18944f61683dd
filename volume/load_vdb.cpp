// OpenVDB files: the grid named by options.grid, else the first float/double grid (half-stored
// float grids included) in the file's grid listing, which OpenVDB keeps ordered by name; double
// grids are converted to float. The grid stays sparse: its domain is the active bounding box and
// its statistics cover the active voxels. The file is read eagerly and must be intact: a short,
// overlong or corrupt file is an error, never a grid with leaves missing.
#include <openvdb/io/Stream.h>
#include <openvdb/tree/LeafManager.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <new>

#include "core/error.h"
#include "volume/detail/vdb_length_check.h"
#include "volume/file_bytes.h"
#include "volume/from_dense.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

bool is_scalar_float(const openvdb::GridBase& g) {
  return g.isType<openvdb::FloatGrid>() || g.isType<openvdb::DoubleGrid>();
}

/// Replaces NaN/Inf voxel and tile values (active or not) with `value`.
void replace_non_finite(openvdb::FloatGrid& grid, float value) {
  openvdb::tree::LeafManager<openvdb::FloatTree> leaves(grid.tree());
  leaves.foreach([value](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
    float* data = leaf.buffer().data();
    for (openvdb::Index n = 0; n < openvdb::FloatTree::LeafNodeType::SIZE; ++n)
      if (!std::isfinite(data[n])) data[n] = value;
  });
  auto it = grid.tree().beginValueAll();
  it.setMaxDepth(openvdb::FloatTree::ValueAllIter::LEAF_DEPTH - 1);
  for (; it; ++it)
    if (!std::isfinite(*it)) it.setValue(value);
}

/// The statistics OpenVDB writes with each grid (active voxel count, active bounding box) must
/// match the tree that was read: a corrupt topology that still parses is caught here.
void check_against_file_stats(const openvdb::GridBase& grid, const std::string& path) {
  const std::string name = "grid '" + grid.getName() + "'";
  using openvdb::GridBase;
  if (auto count = grid.getMetadata<openvdb::Int64Metadata>(GridBase::META_FILE_VOXEL_COUNT)) {
    const openvdb::Index64 active = grid.activeVoxelCount();
    if (count->value() < 0 || openvdb::Index64(count->value()) != active)
      throw Error(path, "corrupt file: " + name + " holds " + std::to_string(active) +
                            " active voxels, its header says " + std::to_string(count->value()));
  }
  auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MIN);
  auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(GridBase::META_FILE_BBOX_MAX);
  if (lo && hi && grid.activeVoxelCount() > 0) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.min() != openvdb::Coord(lo->value()) || box.max() != openvdb::Coord(hi->value()))
      throw Error(path, "corrupt file: the active voxels of " + name +
                            " do not span the bounding box its header gives");
  }
}

}  // namespace

Volume load_vdb(const std::string& path, const LoadOptions& options) {
  const std::uint64_t size = file_size(path);
  detail::check_vdb_lengths(path, size);  // before OpenVDB allocates from a corrupt length
  // Every grid is read eagerly from a stream we own (no delayed loading, no memory mapping) that
  // throws at the first read past the end of the file: OpenVDB does not check its reads, and
  // would go on with sizes it never read (allocating and filling gigabytes for a file cut in its
  // header). The grids must then have used exactly the file's bytes. (A file with several grids
  // is read whole: the price of knowing that the one kept is intact.)
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open file");
  in.exceptions(std::ios::failbit | std::ios::badbit);
  const std::string truncated =
      "file is truncated: its grids need more than its " + std::to_string(size) + " bytes";
  openvdb::GridPtrVec grids;
  try {
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    grids = *stream.getGrids();
  } catch (const std::exception& e) {
    // Once a read has run past the end, whatever OpenVDB then says (a failed decompression, a
    // size read from garbage and too large to allocate) is the truncation.
    if (in.fail()) throw Error(path, truncated);
    if (dynamic_cast<const std::bad_alloc*>(&e))
      throw Error(path, "cannot read OpenVDB file: out of memory (or a corrupt size in the file)");
    throw Error(path, std::string("cannot read OpenVDB file: ") + e.what());
  }
  const std::uint64_t consumed = std::uint64_t(in.tellg());
  if (consumed != size)
    throw Error(path, "corrupt file: its grids end at byte " + std::to_string(consumed) + " of " +
                          std::to_string(size));
  // The order io::File lists grids in: by name.
  std::stable_sort(grids.begin(), grids.end(),
                   [](const auto& a, const auto& b) { return a->getName() < b->getName(); });
  openvdb::GridBase::Ptr base;
  std::string available;
  for (const auto& g : grids) {
    available += (available.empty() ? "" : ", ") + g->getName() + " (" + g->valueType() + ")";
    if (!base && (options.grid.empty() ? is_scalar_float(*g) : g->getName() == options.grid))
      base = g;
  }
  if (!base) {
    if (!options.grid.empty())
      throw Error(path, "no grid named '" + options.grid + "' (grids: " + available + ")");
    throw Error(path, "no float grid (grids: " + (available.empty() ? "none" : available) + ")");
  }
  if (!is_scalar_float(*base))
    throw Error(path, "grid '" + base->getName() + "' holds " + base->valueType() +
                          ", not float or double");
  check_against_file_stats(*base, path);

  Volume v;
  v.path = path;
  v.format = "vdb";
  v.grid_name = base->getName();
  const bool half = base->saveFloatAsHalf();
  if (auto dgrid = openvdb::gridPtrCast<openvdb::DoubleGrid>(base)) {
    auto tree = std::make_shared<openvdb::FloatTree>(dgrid->tree(), float(dgrid->background()), openvdb::TopologyCopy());
    // TopologyCopy fills active voxels with a constant; copy the values themselves.
    auto acc = dgrid->getConstAccessor();
    openvdb::tree::LeafManager<openvdb::FloatTree> leaves(*tree);
    leaves.foreach([&dgrid](openvdb::FloatTree::LeafNodeType& leaf, std::size_t) {
      const auto* src = dgrid->tree().probeConstLeaf(leaf.origin());
      if (!src) return;
      for (openvdb::Index n = 0; n < openvdb::FloatTree::LeafNodeType::SIZE; ++n)
        leaf.setValueOnly(n, float(src->getValue(n)));
    });
    auto it = tree->beginValueAll();
    it.setMaxDepth(openvdb::FloatTree::ValueAllIter::LEAF_DEPTH - 1);
    for (; it; ++it) it.setValue(float(acc.getValue(it.getCoord())));
    v.grid = openvdb::FloatGrid::create(tree);
    v.grid->setTransform(dgrid->transform().copy());
    v.grid->setGridClass(dgrid->getGridClass());
    v.grid->setName(dgrid->getName());
    v.voxel_type = "double";
  } else {
    v.grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    v.voxel_type = half ? "half" : "float";
  }
  if (!v.grid) throw Error(path, "grid '" + v.grid_name + "' is not a float grid");

  switch (v.grid->getGridClass()) {
    case openvdb::GRID_LEVEL_SET: v.grid_class = "level set"; break;
    case openvdb::GRID_FOG_VOLUME: v.grid_class = "fog volume"; break;
    default: v.grid_class = "unknown"; break;
  }
  // Files may say which side is inside and at which value the surface is (isocurv's own
  // datasets do); an explicit --inside still wins.
  Inside inside = v.grid_class == "level set" ? Inside::Below : Inside::Above;
  if (auto meta = v.grid->getMetadata<openvdb::StringMetadata>("inside")) {
    if (meta->value() == "below") inside = Inside::Below;
    if (meta->value() == "above") inside = Inside::Above;
  }
  v.inside = options.inside.value_or(inside);
  v.dense = false;
  v.domain = v.grid->evalActiveVoxelBoundingBox();
  if (v.grid->activeVoxelCount() == 0 || v.domain.empty())
    throw Error(path, "grid '" + v.grid_name + "' is empty (no active voxels)");
  const openvdb::Vec3d voxel = v.grid->voxelSize();
  const openvdb::Vec3d lo = v.grid->indexToWorld(v.domain.min()), hi = v.grid->indexToWorld(v.domain.max());
  for (int i = 0; i < 3; ++i)
    if (!(std::isfinite(voxel[i]) && voxel[i] > 0 && std::isfinite(lo[i]) && std::isfinite(hi[i])))
      throw Error(path, "grid '" + v.grid_name + "' has a degenerate transform (voxel size " +
                            std::to_string(voxel[0]) + " " + std::to_string(voxel[1]) + " " +
                            std::to_string(voxel[2]) + ", or a world box that is not finite)");

  compute_stats(v);
  if (auto meta = v.grid->getMetadata<openvdb::FloatMetadata>("isovalue")) {
    v.stats.suggested_isovalue = meta->value();
    v.stats.suggested_from = "the file's isovalue";
  } else if (auto dmeta = v.grid->getMetadata<openvdb::DoubleMetadata>("isovalue")) {
    v.stats.suggested_isovalue = dmeta->value();
    v.stats.suggested_from = "the file's isovalue";
  }
  if (v.stats.voxels == v.stats.nan_count + v.stats.inf_count)
    throw Error(path, "all active voxels of grid '" + v.grid_name + "' are NaN or Inf");
  if (v.stats.nan_count + v.stats.inf_count > 0 || !std::isfinite(v.grid->background())) {
    const float outside = float(v.inside == Inside::Above ? v.stats.min : v.stats.max);
    replace_non_finite(*v.grid, outside);
    if (!std::isfinite(v.grid->background())) v.grid->tree().root().setBackground(outside, /*updateChildNodes=*/false);
  }
  return v;
}

}  // namespace isocurv::volume
