#pragma once
// The options every command that reads a volume shares (--grid, --inside, raw-file layout).
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "volume/load.h"

namespace isocurv::app {

struct VolumeOptions {
  std::string grid;
  std::string inside;                       // "", "above" or "below"
  std::vector<int> dims;                    // raw: X Y Z
  std::string type;                         // raw voxel type
  std::string endian = "little";            // raw byte order
  std::vector<double> spacing{1, 1, 1};     // raw spacing
  std::vector<double> origin{0, 0, 0};      // raw origin
};

/// Adds --grid, --inside, --dims, --type, --endian, --spacing, --origin to `cmd`.
void add_volume_options(CLI::App& cmd, VolumeOptions& o);
/// Converts parsed options to volume::LoadOptions.
volume::LoadOptions to_load_options(const VolumeOptions& o);

}  // namespace isocurv::app
