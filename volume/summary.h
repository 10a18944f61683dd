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

/// The same as a few aligned human-readable lines.
std::string summary_text(const Volume& v);

}  // namespace isocurv::volume
