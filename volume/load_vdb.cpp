// OpenVDB files: the grid named by options.grid, else the first float/double grid (half-stored
// float grids included) in the file's grid listing, which OpenVDB keeps ordered by name; double
// grids are converted to float. The grid stays sparse: its domain
// is the active bounding box and its statistics cover the active voxels.
#include <openvdb/io/File.h>
#include <openvdb/tree/LeafManager.h>

#include <cmath>

#include "core/error.h"
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

}  // namespace

Volume load_vdb(const std::string& path, const LoadOptions& options) {
  openvdb::GridBase::Ptr base;
  std::string available;
  try {
    openvdb::io::File file(path);
    file.open(/*delayLoad=*/false);
    openvdb::GridPtrVecPtr metas = file.readAllGridMetadata();
    for (const auto& g : *metas) {
      available += (available.empty() ? "" : ", ") + g->getName() + " (" + g->valueType() + ")";
      if (!base && (options.grid.empty() ? is_scalar_float(*g) : g->getName() == options.grid)) base = g;
    }
    if (!base) {
      file.close();
      if (!options.grid.empty()) throw Error(path, "no grid named '" + options.grid + "' (grids: " + available + ")");
      throw Error(path, "no float grid (grids: " + (available.empty() ? std::string("none") : available) + ")");
    }
    if (!is_scalar_float(*base))
      throw Error(path, "grid '" + base->getName() + "' holds " + base->valueType() + ", not float or double");
    base = file.readGrid(base->getName());
    file.close();
  } catch (const openvdb::Exception& e) {
    throw Error(path, std::string("cannot read OpenVDB file: ") + e.what());
  }

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

  compute_stats(v);
  if (auto meta = v.grid->getMetadata<openvdb::FloatMetadata>("isovalue")) v.stats.suggested_isovalue = meta->value();
  else if (auto dmeta = v.grid->getMetadata<openvdb::DoubleMetadata>("isovalue")) v.stats.suggested_isovalue = dmeta->value();
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
