// libFuzzer harness for one volume format (FUZZ_FORMAT, set by fuzz/CMakeLists.txt): the input
// becomes a file of that format and goes through volume::load. A load may fail only with
// isocurv::Error; a load that succeeds must keep what it promises (fuzz/README.md).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "volume/load.h"
#include "volume/voxel_type.h"

namespace {

using isocurv::fuzz::input_files;
using isocurv::fuzz::require;
using namespace isocurv::volume;

const std::string kFormat = FUZZ_FORMAT;
/// Formats with a header and a detached data file: the input holds both, split at this line;
/// the seeds' headers name the data file "data.raw".
const std::string kSplit = "\n#isocurv-fuzz-data#\n";

/// Formats whose payload may be compressed (deflate, run lengths): a load may decode up to about
/// 1032 bytes per byte of input. Every other format decodes at most one voxel per input byte.
bool may_compress() {
  return kFormat == "nrrd" || kFormat == "nhdr" || kFormat == "mha" || kFormat == "mhd" ||
         kFormat == "nii_gz" || kFormat == "vti" || kFormat == "vol" || kFormat == "raw_gz" ||
         kFormat == "slc";
}

bool finite3(const openvdb::Vec3d& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

void check(const Volume& v, std::uint64_t input_bytes, std::uint64_t exact_payload) {
  require(v.grid != nullptr, "no grid");
  require(!v.domain.empty(), "empty domain");
  const openvdb::Vec3d spacing = v.spacing();
  require(finite3(spacing) && spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0,
          "spacing not finite and positive");
  const auto& xform = v.grid->transform();
  require(finite3(xform.indexToWorld(v.domain.min().asVec3d())) &&
              finite3(xform.indexToWorld(v.domain.max().asVec3d())),
          "world box not finite");
  const ValueStats& s = v.stats;
  require(std::isfinite(s.min) && std::isfinite(s.max) && s.min <= s.max, "value range");
  require(std::isfinite(s.mean) && s.mean >= s.min - 1e-6 * std::fabs(s.min) - 1e-6 &&
              s.mean <= s.max + 1e-6 * std::fabs(s.max) + 1e-6,
          "mean outside the value range");
  require(std::isfinite(s.suggested_isovalue), "suggested isovalue not finite");
  require(s.nan_count + s.inf_count < s.voxels, "no finite voxel");
  std::uint64_t binned = 0;
  for (std::uint64_t b : s.histogram) binned += b;
  require(s.histogram.size() == 256 && binned == s.voxels - s.nan_count - s.inf_count,
          "histogram does not count the finite voxels");
  require(std::isfinite(v.grid->background()), "background not finite");
  if (!v.dense) {
    require(s.voxels == v.grid->activeVoxelCount(), "stats do not cover the active voxels");
    return;
  }
  const std::uint64_t count = v.domain.volume();
  require(s.voxels == count, "stats do not cover the domain");
  const auto type = parse_voxel_type(v.voxel_type);
  const std::uint64_t voxel_bytes = type ? voxel_size(*type) : 1;
  if (exact_payload) {
    require(count * voxel_bytes == exact_payload, "voxels do not use exactly the raw data");
  } else if (may_compress()) {
    require(count * voxel_bytes <= input_bytes * 1040 + 1024, "more voxels than the data can hold");
  } else {
    require(count <= input_bytes, "more voxels than bytes in the file");
  }
}

/// Raw volumes take their layout from options or the file name: the first 6 input bytes choose
/// it, the rest is the data.
std::string raw_input(const std::uint8_t* data, std::size_t size, LoadOptions& options,
                      std::uint64_t& payload) {
  static const char* const types[] = {"uint8", "int8",  "uint16", "int16",
                                      "uint32", "int32", "float",  "double"};
  if (size < 6) return {};
  const int dims[3] = {1 + data[0] % 16, 1 + data[1] % 16, 1 + data[2] % 16};
  const std::string type = types[data[3] % 8];
  const bool big = data[4] & 1;
  const bool gz = kFormat == "raw_gz";
  std::string name = "input";
  if (data[5] & 1) {
    name += "_" + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
            std::to_string(dims[2]) + "_" + type + (big ? "be" : "le");
  } else {
    options.raw.dims = {dims[0], dims[1], dims[2]};
    options.raw.type = type;
    options.raw.big_endian = big;
  }
  name += gz ? ".raw.gz" : ".raw";
  payload = gz ? 0 : size - 6;
  return input_files().write(name, data + 6, size - 6);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  input_files().clear();
  LoadOptions options;
  std::uint64_t exact_payload = 0;
  std::string path;
  if (kFormat == "raw" || kFormat == "raw_gz") {
    path = raw_input(data, size, options, exact_payload);
    if (path.empty()) return 0;
  } else if (kFormat == "nhdr" || kFormat == "mhd") {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::size_t split = text.find(kSplit);
    const std::size_t header = split == std::string::npos ? size : split;
    path = input_files().write("input." + kFormat, data, header);
    if (split != std::string::npos)
      input_files().write("data.raw", data + split + kSplit.size(), size - split - kSplit.size());
  } else {
    std::string ext = kFormat;
    if (ext == "nii_gz") ext = "nii.gz";
    path = input_files().write("input." + ext, data, size);
  }
  try {
    const Volume v = load(path, options);
    check(v, size, exact_payload);
  } catch (const isocurv::Error&) {
    // the one allowed failure
  }
  return 0;
}
