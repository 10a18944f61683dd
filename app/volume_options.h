#pragma once
// The options every command that reads a volume shares (--grid, --inside, raw-file layout,
// --spacing and --origin overrides).
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "volume/load.h"

namespace isocurv::app {

/// Each field is empty when the option was not given, so "not given" never looks like a value.
struct VolumeOptions {
  std::string grid;             // .vdb grid name
  std::string inside;           // "above" or "below"
  std::vector<int> dims;        // raw: X Y Z
  std::string type;             // raw voxel type
  std::string endian;           // raw byte order: "little" or "big"
  std::vector<double> spacing;  // any format: overrides the header
  std::vector<double> origin;   // any format: overrides the header
  std::optional<int> level, time_point, channel;  // Zarr: multiscale level, time point, channel

  /// The options given, as they are spelled on the command line ("--grid", "--dims", ...).
  std::vector<std::string> given() const;
};

/// Adds --grid, --inside, --dims, --type, --endian, --spacing, --origin, and Zarr's --level,
/// --time-point and --channel to `cmd`.
void add_volume_options(CLI::App& cmd, VolumeOptions& o);
/// Converts parsed options to volume::LoadOptions (volume::load rejects those that cannot apply
/// to the file's format).
volume::LoadOptions to_load_options(const VolumeOptions& o);

}  // namespace isocurv::app
