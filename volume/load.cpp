// volume::load: picks the loader by file extension.
#include "volume/load.h"

#include <openvdb/openvdb.h>

#include <array>
#include <cmath>
#include <new>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"
#include "volume/zarr.h"

namespace isocurv::volume {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

enum class Format { vdb, nrrd, metaimage, nifti, vtk_image, dgtal_vol, raw, zarr, unknown };

Format format_of(const std::string& path) {
  const std::string name = to_lower(path);
  if (ends_with(name, ".vdb")) return Format::vdb;
  if (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) return Format::nrrd;
  if (ends_with(name, ".mhd") || ends_with(name, ".mha")) return Format::metaimage;
  if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) return Format::nifti;
  if (ends_with(name, ".vti") || ends_with(name, ".vtk") || ends_with(name, ".slc"))
    return Format::vtk_image;
  if (ends_with(name, ".vol")) return Format::dgtal_vol;
  if (ends_with(name, ".raw") || ends_with(name, ".raw.gz") || ends_with(name, ".bin-gz") ||
      ends_with(name, ".bin.gz") || ends_with(name, ".bin"))
    return Format::raw;
  return Format::unknown;
}

/// An option that cannot apply to the file's format is an error naming it, not silently ignored.
void check_options_apply(const std::string& path, Format format, const LoadOptions& o) {
  if (format != Format::raw) {
    const char* given = o.raw.dims != std::array<int, 3>{0, 0, 0} ? "--dims"
                        : !o.raw.type.empty()                     ? "--type"
                        : o.raw.big_endian                        ? "--endian"
                                                                  : nullptr;
    if (given)
      throw Error(
          path, std::string(given) +
                    " applies to headerless .raw files only; this file's header gives its layout");
  }
  if (format != Format::vdb && !o.grid.empty())
    throw Error(path, "--grid applies to .vdb files only (this format holds one volume)");
  if (format != Format::zarr) {
    const char* given = o.level ? "--level" : o.time_point ? "--time-point" : o.channel ? "--channel" : nullptr;
    if (given) throw Error(path, std::string(given) + " applies to Zarr stores only");
  }
  for (int i = 0; i < 3; ++i) {
    if (o.spacing && (!std::isfinite((*o.spacing)[i]) || (*o.spacing)[i] <= 0))
      throw Error(path, "--spacing needs three positive finite numbers");
    if (o.origin && !std::isfinite((*o.origin)[i]))
      throw Error(path, "--origin needs three finite numbers");
  }
}

/// Replaces a loaded .vdb's voxel size and origin (the dense formats apply the override in
/// finish_dense, before their axes are normalised), keeping its axis directions.
void override_vdb_geometry(Volume& v, const LoadOptions& o) {
  if (!o.spacing && !o.origin) return;
  const openvdb::math::Transform& xform = v.grid->transform();
  if (!xform.isLinear())
    throw Error(v.path, "--spacing and --origin cannot replace a non-linear (frustum) transform");
  // OpenVDB matrices act on row vectors: row i is index axis i in world space, row 3 the origin.
  const openvdb::Mat4d m = xform.baseMap()->getAffineMap()->getMat4();
  std::array<double, 3> spacing{}, origin{};
  std::array<std::array<double, 3>, 3> axes{};
  for (int i = 0; i < 3; ++i) {
    const openvdb::Vec3d row(m(i, 0), m(i, 1), m(i, 2));
    spacing[std::size_t(i)] = row.length();
    for (int j = 0; j < 3; ++j)
      axes[std::size_t(i)][std::size_t(j)] = row[j] / spacing[std::size_t(i)];
    origin[std::size_t(i)] = m(3, i);
  }
  if (o.spacing) v.file_spacing = openvdb::Vec3d(spacing[0], spacing[1], spacing[2]);
  if (o.origin) v.file_origin = openvdb::Vec3d(origin[0], origin[1], origin[2]);
  v.grid->setTransform(
      make_transform(o.spacing.value_or(spacing), o.origin.value_or(origin), axes));
}

}  // namespace

Volume load(const std::string& path, const LoadOptions& options) {
  // A Zarr store is a folder; any other volume is a file ("file not found" before anything else).
  const bool zarr = is_zarr_store(path);
  if (!zarr) file_size(path);
  const Format format = zarr ? Format::zarr : format_of(path);
  if (format == Format::unknown)
    throw Error(path,
                "unknown volume file extension (supported: .vdb .nrrd .nhdr .mhd .mha .nii .nii.gz "
                ".vti .vtk .slc .vol .raw .raw.gz .bin-gz, and Zarr stores: a folder with .zarray, "
                ".zattrs, .zgroup or zarr.json)");
  check_options_apply(path, format, options);
  try {
    switch (format) {
      case Format::vdb: {
        openvdb::initialize();
        Volume v = load_vdb(path, options);
        override_vdb_geometry(v, options);
        return v;
      }
      case Format::nrrd:
        return load_nrrd(path, options);
      case Format::metaimage:
        return load_metaimage(path, options);
      case Format::nifti:
        return load_nifti(path, options);
      case Format::vtk_image:
        return load_vtk_image(path, options);
      case Format::dgtal_vol:
        return load_dgtal_vol(path, options);
      case Format::raw:
        return load_raw(path, options);
      case Format::zarr:
        return load_zarr(path, options);
      case Format::unknown:
        break;
    }
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(path, "out of memory while loading");
  } catch (const std::exception& e) {
    // Library exceptions (OpenVDB, VTK, the standard library) become one-line errors too.
    throw Error(path, e.what());
  }
  throw Error(path, "unknown volume format");
}

}  // namespace isocurv::volume
