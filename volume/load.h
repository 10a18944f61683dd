#pragma once
// volume::load: any supported volume file -> Volume (an openvdb::FloatGrid with its transform).
#include <array>
#include <optional>
#include <string>

#include "volume/volume.h"

namespace isocurv::volume {

/// How to read a headerless .raw / .raw.gz file (ignored for other formats).
struct RawOptions {
  std::array<int, 3> dims{0, 0, 0};          ///< X Y Z voxel counts, X fastest in the file
  std::string type;                          ///< uint8 int8 uint16 int16 uint32 int32 float double
  bool big_endian = false;
  std::array<double, 3> spacing{1, 1, 1};    ///< world units per voxel
  std::array<double, 3> origin{0, 0, 0};     ///< world position of the first voxel
};

struct LoadOptions {
  std::string grid;               ///< .vdb: grid name; empty picks the first float/double/half grid
  std::optional<Inside> inside;   ///< override which side is the object
  RawOptions raw;
};

/// Loads `path`, chosen by extension: .vdb, .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, .vti, .vtk,
/// .vol (DGtal), .raw/.raw.gz (with options.raw). Non-finite voxels are counted in stats and
/// replaced by an outside value. Throws isocurv::Error("<path>: <problem>") on any bad input.
Volume load(const std::string& path, const LoadOptions& options = {});

}  // namespace isocurv::volume
