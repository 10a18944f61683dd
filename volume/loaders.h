#pragma once
// One loader per file format; volume::load (load.cpp) picks one by extension. Each takes the
// path and the load options and returns a finished Volume, or throws Error(path, problem).
// Tested in tests/volume/test_loaders.cpp and tests/volume/test_bad_input.cpp.
#include <string>

#include "volume/load.h"

namespace isocurv::volume {

Volume load_vdb(const std::string& path, const LoadOptions& options);         ///< .vdb (OpenVDB)
Volume load_nrrd(const std::string& path, const LoadOptions& options);        ///< .nrrd, .nhdr
Volume load_metaimage(const std::string& path, const LoadOptions& options);   ///< .mhd, .mha
Volume load_nifti(const std::string& path, const LoadOptions& options);       ///< .nii, .nii.gz
Volume load_vtk_image(const std::string& path, const LoadOptions& options);   ///< .vti, .vtk (VTK readers); .slc
Volume load_slc(const std::string& path, const LoadOptions& options);         ///< .slc (VolVis), via load_vtk_image
Volume load_dgtal_vol(const std::string& path, const LoadOptions& options);   ///< .vol (DGtal VOL)
Volume load_raw(const std::string& path, const LoadOptions& options);         ///< .raw, .raw.gz, .bin-gz
Volume load_zarr(const std::string& path, const LoadOptions& options);        ///< Zarr v2/v3, OME-NGFF (zarr.h)

}  // namespace isocurv::volume
