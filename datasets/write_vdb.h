#pragma once
// Writing a sampled analytic field as a small self-describing .vdb file.
#include <string>

#include "datasets/field.h"
#include "volume/volume.h"

namespace isocurv::datasets {

/// Writes `v` (from sample(field, ...)) to `path` as a one-grid .vdb, atomically (temporary name,
/// then rename). The grid keeps v's name ("density" / "levelset"), class and transform; grid and
/// file metadata carry "isovalue" (double), "inside" ("above" / "below"), "field" (catalogue name)
/// and "description". Throws isocurv::Error naming the path when writing fails.
void write_vdb(const Field& field, const volume::Volume& v, const std::string& path);

}  // namespace isocurv::datasets
