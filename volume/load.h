#pragma once
// volume::load: any supported volume file -> Volume (an openvdb::FloatGrid with its transform).
// Tested in tests/volume/test_loaders.cpp, tests/volume/test_bad_input.cpp.
#include <array>
#include <optional>
#include <string>

#include "volume/volume.h"

namespace isocurv::volume {

/// How to read a headerless .raw / .raw.gz file. A raw file's name may carry its layout
/// (`_<X>x<Y>x<Z>_<type>[le|be]`); a field set here always wins over the name. Giving any of
/// dims, type or big_endian for another format is an error (its header gives the layout).
struct RawOptions {
  std::array<int, 3> dims{0, 0, 0};          ///< X Y Z voxel counts, X fastest; {0,0,0}: not given
  std::string type;                          ///< uint8 int8 uint16 int16 uint32 int32 float double; "": not given
  std::optional<bool> big_endian;            ///< byte order; unset: from the name, else little
  std::array<double, 3> spacing{1, 1, 1};    ///< world units per voxel (what a header would say)
  std::array<double, 3> origin{0, 0, 0};     ///< world position of the first voxel (likewise)
};

struct LoadOptions {
  std::string grid;               ///< .vdb: grid name; empty picks the first float/double/half grid
                                  ///< (giving one for another format is an error)
  std::optional<Inside> inside;   ///< override which side is the object
  RawOptions raw;
  /// Override the spacing / origin of every format (the header's, a .vdb's transform, or raw's
  /// values above): spacing along the file's own axes, origin the world position of the file's
  /// first voxel (index 0 0 0 for .vdb). The file's values are kept in Volume::file_spacing /
  /// file_origin. Spacing must be positive and finite, the origin finite.
  std::optional<std::array<double, 3>> spacing, origin;
  /// Read only the index-z slices [first, last] (rounded out to whole 8-voxel blocks, clamped to
  /// the file) where the format stores its voxels uncompressed (raw, NRRD raw encoding,
  /// MetaImage binary data, .nii): the
  /// Volume's `slab` says what was read. Other formats and encodings read everything (no `slab`).
  /// For a rank of a distributed run (app/distributed.cpp).
  std::optional<std::array<int, 2>> z_slab;
  /// The value non-finite voxels and the grid's background take, instead of the finite minimum
  /// (maximum when the object is below): a slab's ranks use the whole volume's.
  std::optional<float> outside;
  /// Zarr stores (volume/zarr.h): the multiscale level (0 the finest; unset: the finest that
  /// fits zarr_memory_budget()), and the index along a time ("t") and a channel ("c") axis
  /// (unset: 0). Giving any of them for another format is an error.
  std::optional<int> level, time_point, channel;
};

/// Loads `path`, chosen by extension: .vdb, .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, .vti, .vtk,
/// .vol (DGtal), .raw/.raw.gz (with options.raw), and Zarr stores (a folder holding .zarray,
/// .zattrs, .zgroup or zarr.json, or named *.zarr; volume/zarr.h). Non-finite voxels are counted in stats and
/// replaced by an outside value. Throws isocurv::Error("<path>: <problem>") on any bad input.
Volume load(const std::string& path, const LoadOptions& options = {});

}  // namespace isocurv::volume
