#pragma once
// The whole volume's value statistics from the ranks' shares of it (each rank read an even share
// of the slices: volume::LoadOptions::z_slab), equal to what one process loading the whole file
// computes: range, counts, the 256-bin histogram and so the suggested (Otsu) isovalue. The mean
// may differ in its last digits (the order of the sums).
// Tested in tests/dist/test_distributed.cpp (the suggested isovalue agrees with one process).
#include "dist/world.h"
#include "volume/volume.h"

namespace isocurv::dist {

/// Collective. `share` holds this rank's slices (share->slab; shares do not overlap and together
/// cover the file) with the statistics of those slices, or is null for a rank without a share
/// (more ranks than 8-slice blocks). Returns the whole volume's. `path` names the file in errors.
/// @throw Error (every rank) when no voxel of the file is finite.
volume::ValueStats reduce_stats(const World& world, const volume::Volume* share, const std::string& path);

}  // namespace isocurv::dist
