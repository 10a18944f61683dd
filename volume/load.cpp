// volume::load: picks the loader by file extension.
#include "volume/load.h"

#include <openvdb/openvdb.h>

#include <new>

#include "core/error.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

Volume load(const std::string& path, const LoadOptions& options) {
  file_size(path);  // "file not found" before anything else
  const std::string name = to_lower(path);
  try {
    if (ends_with(name, ".vdb")) {
      openvdb::initialize();
      return load_vdb(path, options);
    }
    if (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) return load_nrrd(path, options);
    if (ends_with(name, ".mhd") || ends_with(name, ".mha")) return load_metaimage(path, options);
    if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) return load_nifti(path, options);
    if (ends_with(name, ".vti") || ends_with(name, ".vtk") || ends_with(name, ".slc"))
      return load_vtk_image(path, options);
    if (ends_with(name, ".vol")) return load_dgtal_vol(path, options);
    if (ends_with(name, ".raw") || ends_with(name, ".raw.gz") || ends_with(name, ".bin-gz") ||
        ends_with(name, ".bin.gz") || ends_with(name, ".bin"))
      return load_raw(path, options);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(path, "out of memory while loading");
  } catch (const std::exception& e) {
    // Library exceptions (OpenVDB, VTK, the standard library) become one-line errors too.
    throw Error(path, e.what());
  }
  throw Error(path,
              "unknown volume file extension (supported: .vdb .nrrd .nhdr .mhd .mha .nii .nii.gz .vti .vtk .slc "
              ".vol .raw .raw.gz .bin-gz)");
}

}  // namespace isocurv::volume
