#pragma once
// Zarr stores (v2 and v3, local folders) and OME-NGFF multiscale images (0.4 and 0.5): what a
// store holds, for `isocurv info`, and which level volume::load reads. volume::load (load_zarr)
// reads one level, one time point and one channel into memory; docs/big-volumes.md.
// Tested in tests/volume/test_zarr.cpp.
#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/load.h"

namespace isocurv::volume {

/// True when volume::load reads `path` as Zarr: a folder holding .zarray, .zattrs, .zgroup or
/// zarr.json, or a path named *.zarr (which then must be a store).
bool is_zarr_store(const std::string& path);

/// The memory a loaded level may take: half the machine's physical memory.
std::uint64_t zarr_memory_budget();

/// Bytes a level of `voxels` voxels takes once loaded (the decoded floats and the grid).
constexpr std::uint64_t zarr_bytes_per_voxel = 8;

/// One resolution level of a store.
struct ZarrLevelInfo {
  std::string path;                     ///< the dataset's path in the store ("0"), "." for a bare array
  std::vector<long long> shape;         ///< array order
  std::vector<long long> chunks;        ///< the chunk (or shard) shape, array order
  std::vector<long long> inner_chunks;  ///< sharded: the inner chunks' shape; else empty
  std::array<long long, 3> dims{0, 0, 0};  ///< the volume read: X Y Z voxels
  std::array<double, 3> spacing{1, 1, 1}, origin{0, 0, 0};  ///< X Y Z
  std::uint64_t bytes = 0;              ///< dims' voxels * zarr_bytes_per_voxel
  bool fits = false;                    ///< bytes <= the memory budget
};

/// What a store holds.
struct ZarrInfo {
  std::string path;
  int zarr_format = 2;
  std::string ome_version;              ///< "" for a bare array
  std::vector<std::string> axes;        ///< array order, e.g. t c z y x
  std::vector<std::string> axis_units;  ///< as written, "" when absent
  std::string length_unit;              ///< short ("um"), "" when unknown or the axes differ
  std::string voxel_type;               ///< "uint16", ...
  std::string byte_order;               ///< "little", "big" or "" (one-byte types)
  std::string codecs;                   ///< the finest level's pipeline, outermost first
  double fill_value = 0;
  std::uint64_t budget = 0;             ///< zarr_memory_budget()
  int default_level = -1;               ///< the finest level that fits; -1: none
  std::vector<ZarrLevelInfo> levels;    ///< finest first
};

/// Reads a store's metadata (no chunk); throws Error naming the file on a bad store.
ZarrInfo describe_zarr(const std::string& path);

/// The level load reads: options.level (checked against the levels and the budget), else the
/// default level; throws when none fits.
int choose_zarr_level(const ZarrInfo& info, const LoadOptions& options);

/// For `info --json`: {"zarr_format", "ome_version", "axes", "levels": [{"path", "shape",
/// "chunks", "spacing", "origin", ...}], "codecs", "dtype", "length_unit", "level_read", ...}.
nlohmann::json zarr_summary_json(const ZarrInfo& info, int level_read);
/// The same as aligned text lines.
std::string zarr_summary_text(const ZarrInfo& info, int level_read);

}  // namespace isocurv::volume
