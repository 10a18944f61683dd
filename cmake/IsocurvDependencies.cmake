# Finds every dependency; a missing one stops configuration with the Debian package to install.
function(isocurv_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "isocurv: ${what} not found. Install it with: apt-get install ${package}"
                        " (or run scripts/setup.sh as root, which installs every dependency)")
  endif()
endfunction()

find_package(Threads REQUIRED)
find_package(ZLIB QUIET)
isocurv_require(ZLIB_FOUND "zlib" zlib1g-dev)
# Zarr chunk codecs (volume/detail/zarr_chunks.cpp): zstd and blosc, as plain library paths.
find_path(ISOCURV_ZSTD_INCLUDE zstd.h)
find_library(ISOCURV_ZSTD_LIBRARY zstd)
if(ISOCURV_ZSTD_INCLUDE AND ISOCURV_ZSTD_LIBRARY)
  set(ISOCURV_ZSTD_FOUND TRUE)
endif()
isocurv_require(ISOCURV_ZSTD_FOUND "zstd" libzstd-dev)
find_path(ISOCURV_BLOSC_INCLUDE blosc.h)
find_library(ISOCURV_BLOSC_LIBRARY blosc)
if(ISOCURV_BLOSC_INCLUDE AND ISOCURV_BLOSC_LIBRARY)
  set(ISOCURV_BLOSC_FOUND TRUE)
endif()
isocurv_require(ISOCURV_BLOSC_FOUND "blosc" libblosc-dev)

find_package(TBB QUIET CONFIG)
isocurv_require(TBB_FOUND "TBB" libtbb-dev)

include(FindOpenVDBDebian)
isocurv_require(OpenVDB_FOUND "OpenVDB" "libopenvdb-dev libboost-iostreams-dev")

find_package(OpenCL QUIET)
isocurv_require(OpenCL_FOUND "OpenCL (ICD loader and headers)" "ocl-icd-opencl-dev opencl-headers pocl-opencl-icd")
if(NOT EXISTS "${OpenCL_INCLUDE_DIR}/CL/opencl.hpp")
  message(FATAL_ERROR "isocurv: OpenCL C++ bindings (CL/opencl.hpp) not found. Install it with: apt-get install opencl-clhpp-headers")
endif()

find_package(Eigen3 QUIET NO_MODULE)
isocurv_require(Eigen3_FOUND "Eigen" libeigen3-dev)

find_package(VTK QUIET COMPONENTS
  CommonCore CommonDataModel CommonExecutionModel FiltersCore FiltersGeneral FiltersSources
  IOXML IOParallelXML IOLegacy IOImage IOPLY IOGeometry ImagingCore
  RenderingCore RenderingOpenGL2 RenderingAnnotation InteractionStyle InteractionWidgets IOExport)
isocurv_require(VTK_FOUND "VTK 9" libvtk9-dev)

find_package(CLI11 QUIET CONFIG)
if(NOT CLI11_FOUND AND NOT EXISTS /usr/include/CLI/CLI.hpp)
  isocurv_require(CLI11_FOUND "CLI11" libcli11-dev)
endif()
find_package(nlohmann_json QUIET CONFIG)
isocurv_require(nlohmann_json_FOUND "nlohmann-json" nlohmann-json3-dev)

if(ISOCURV_BUILD_TESTS)
  find_package(GTest QUIET)
  isocurv_require(GTest_FOUND "GoogleTest" libgtest-dev)
endif()
