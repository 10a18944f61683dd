#pragma once
// The scalar grids of a .vdb file, for reading a multi-grid file as the frames of a series.
// Tested in tests/volume/test_vdb_lengths.cpp.
#include <string>
#include <vector>

namespace isocurv::volume {

/// The names of the float, double and half grids of the .vdb at `path`, in natural order
/// (core/natural_order.h: frame_2 before frame_10), read from the file's grid descriptors and
/// metadata only (no voxels). Grids of other value types are left out.
/// @throw Error naming the file when it cannot be opened or its header cannot be read (a grid's
///        voxels are only checked when volume::load reads it).
std::vector<std::string> vdb_grid_names(const std::string& path);

}  // namespace isocurv::volume
