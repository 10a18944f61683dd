#pragma once
// The loaded volume every later stage reads: an OpenVDB float grid plus what was learned loading it.
// Tested in tests/mc/flying_edges.h.
#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace isocurv::volume {

/// Which side of the isovalue is the object (DESIGN.md): Above for densities and CT,
/// Below for level sets (negative inside).
enum class Inside { Above, Below };

/// Value statistics over the finite voxels of the data domain.
struct ValueStats {
  double min = 0, max = 0;         ///< finite value range
  double mean = 0;
  std::uint64_t voxels = 0;        ///< voxels counted (finite + non-finite)
  std::uint64_t nan_count = 0;     ///< NaN voxels (replaced by an outside value on load)
  std::uint64_t inf_count = 0;     ///< +-Inf voxels (likewise replaced)
  std::vector<std::uint64_t> histogram;  ///< 256 equal bins over [min, max]
  double suggested_isovalue = 0;   ///< 0 for level sets, else Otsu's threshold on the histogram
  /// Where suggested_isovalue came from: "Otsu", "level set zero", or "the file's isovalue"
  /// (a .vdb grid's "isovalue" metadata).
  std::string suggested_from = "Otsu";
};

/// True for the integer voxel types ("uint8", "int8", "uint16", "int16", "uint32", "int32"), whose
/// values are exact integers (quantised data); false for "float", "double", "half" and unknown.
inline bool is_integer_type(const std::string& voxel_type) {
  for (const char* t : {"uint8", "int8", "uint16", "int16", "uint32", "int32"})
    if (voxel_type == t) return true;
  return false;
}

/// A volume as an OpenVDB FloatGrid. The grid's transform maps index space to world space
/// (spacing, origin, and for NIfTI/MetaImage a direction matrix). Dense files become a grid
/// whose data domain is `domain` (index space, inclusive); sparse .vdb grids have
/// `dense = false` and their domain is the active bounding box.
struct Volume {
  openvdb::FloatGrid::Ptr grid;
  std::string path;               ///< file it came from
  std::string format;             ///< "vdb", "nrrd", "metaimage", "nifti", "vti", "vtk", "dgtal-vol", "raw", "generated"
  std::string voxel_type;         ///< type on disk: "uint8", "int16", "uint16", "int32", "float", "double", "half"
  std::string grid_class;         ///< "level set", "fog volume" or "unknown"
  std::string grid_name;          ///< VDB grid name, or the array name for VTK files
  /// What the world axes mean anatomically, as three letters for +x +y +z: "RAS" (NIfTI),
  /// "LPS" (MetaImage, ITK), or NRRD's `space` ("RAS", "LAS", "LPS"); empty when unknown.
  std::string world_space;
  /// The world length unit the header states ("mm", "m", "um"): NIfTI's xyzt_units, NRRD's
  /// `space units`, MetaImage's millimetres (MetaIO's and ITK's convention; the format has no
  /// unit field); empty when the file says nothing (raw, .vol, .vti, .vdb).
  std::string length_unit;
  bool dense = true;              ///< true when every voxel of `domain` was stored in the file
  openvdb::CoordBBox domain;      ///< index-space data domain (inclusive)
  Inside inside = Inside::Above;  ///< which side is the object
  ValueStats stats;
  /// Set when only part of the file was read (LoadOptions::z_slab, a rank of a distributed run):
  /// the voxels the grid holds. `domain` stays the whole file's; the rest of it reads as the
  /// background, and `stats` describe the part read until the caller replaces them.
  std::optional<openvdb::CoordBBox> slab;
  /// What the file said, kept when LoadOptions::spacing / origin overrode it (else unset).
  std::optional<openvdb::Vec3d> file_spacing, file_origin;

  /// Voxel spacing (world units per index step along each axis).
  openvdb::Vec3d spacing() const { return grid->transform().voxelSize(); }
  /// World position of index (0,0,0).
  openvdb::Vec3d origin() const { return grid->transform().indexToWorld(openvdb::Vec3d(0, 0, 0)); }
};

}  // namespace isocurv::volume
