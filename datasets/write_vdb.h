#pragma once
// Writing a sampled analytic field as a small self-describing .vdb file.
#include <string>
#include <vector>

#include "datasets/field.h"
#include "volume/volume.h"

namespace isocurv::datasets {

/// Writes `v` (from sample(field, ...)) to `path` as a one-grid .vdb, atomically (temporary name,
/// then rename). The grid keeps v's name ("density" / "levelset"), class and transform; grid and
/// file metadata carry "isovalue" (double), "inside" ("above" / "below"), "field" (catalogue name)
/// and "description". Throws isocurv::Error naming the path when writing fails.
void write_vdb(const Field& field, const volume::Volume& v, const std::string& path);

/// One grid of a multi-grid .vdb: the sampled field, the grid's name, and its time (grid
/// metadata "time", double).
struct NamedGrid {
  const Field* field = nullptr;
  const volume::Volume* volume = nullptr;
  std::string name;
  double time = 0;
};

/// Writes several sampled fields into one .vdb, atomically, one grid per entry under its name,
/// each with the metadata write_vdb gives plus "time" (a multi-grid file read as a time series:
/// frames ordered by grid name). Throws isocurv::Error naming the path when writing fails.
void write_vdb_grids(const std::vector<NamedGrid>& grids, const std::string& path);

}  // namespace isocurv::datasets
