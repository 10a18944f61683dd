#pragma once
// What `isocurv info` prints about a loaded volume.
// Tested in tests/volume/test_summary.cpp.
#include <nlohmann/json.hpp>

#include <string>

#include "volume/volume.h"

namespace isocurv::volume {

/// Machine-readable summary: path, format, grid name and class, voxel type, dimensions, spacing,
/// origin, inside side, value range, mean, NaN/Inf counts, histogram summary, suggested isovalue.
nlohmann::json summary_json(const Volume& v);

/// The number of labels when `v` looks like a label map (a segmentation, each non-zero value an
/// object): integer voxels, values 0 to 255 with 0 holding at least half the voxels, and 2 to 64
/// distinct non-zero values, from the histogram (one bin per value there); 0 otherwise. CT and MR
/// scans hold more values, and a 0/1 mask is one object. A hint for `info`, not a rule: --labels
/// decides by itself (labels/label_map.h).
std::size_t label_map_hint(const Volume& v);

/// The same as a few aligned human-readable lines.
std::string summary_text(const Volume& v);

}  // namespace isocurv::volume
