// libFuzzer harness for one volume format (FUZZ_FORMAT, set by fuzz/CMakeLists.txt): the input
// becomes a file of that format and goes through volume::load. A load may fail only with
// isocurv::Error; a load that succeeds must keep what it promises (fuzz/README.md).
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "core/error.h"
#include "fuzz/fuzz_input.h"
#include "fuzz/vtk_xml_oracle.h"
#include "volume/load.h"
#include "volume/voxel_type.h"

namespace {

using isocurv::fuzz::input_files;
using isocurv::fuzz::raw_appended_arrays;
using isocurv::fuzz::RawArray;
using isocurv::fuzz::require;
using isocurv::fuzz::type_bytes;
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

/// What a NRRD header says, read independently of the loader: each field once, finite non-zero
/// spacings that the volume keeps (as lengths), and raw data exactly as long as the sizes need
/// (`data_bytes`: the detached data file's size; for an attached header, what follows it).
void check_nrrd(const Volume& v, const std::string& header, std::uint64_t data_bytes, bool detached) {
  std::map<std::string, std::string> fields;
  std::size_t pos = header.find('\n');
  while (pos != std::string::npos && pos + 1 < header.size()) {
    const std::size_t end = header.find('\n', pos + 1);
    std::string line = header.substr(pos + 1, end == std::string::npos ? std::string::npos : end - pos - 1);
    pos = end;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {  // the end of an attached header
      if (!detached) data_bytes = end == std::string::npos ? 0 : header.size() - end - 1;
      break;
    }
    if (line[0] == '#' || line.find(":=") != std::string::npos) continue;
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon);
    for (char& c : key) c = char(std::tolower(static_cast<unsigned char>(c)));
    while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
    while (!key.empty() && std::isspace(static_cast<unsigned char>(key.front()))) key.erase(0, 1);
    if (key == "datafile") key = "data file";
    require(fields.emplace(key, line.substr(colon + 2)).second, "a NRRD field given twice loaded");
  }
  if (fields.count("spacings") && !fields.count("space directions")) {
    const char* p = fields["spacings"].c_str();
    for (int i = 0; i < 3; ++i) {
      char* end = nullptr;
      const double s = std::strtod(p, &end);
      if (end == p) return;  // the loader parsed it otherwise; nothing to compare
      p = end;
      require(std::isfinite(s) && s != 0, "a NaN, infinite or zero NRRD spacing loaded");
      require(std::fabs(v.spacing()[i] - std::fabs(s)) <= 1e-9 * std::fabs(s), "NRRD spacing not kept");
    }
  }
  std::string encoding = fields.count("encoding") ? fields["encoding"] : "";
  while (!encoding.empty() && std::isspace(static_cast<unsigned char>(encoding.back()))) encoding.pop_back();
  const auto type = parse_voxel_type(v.voxel_type);
  std::string data_file = fields.count("data file") ? fields["data file"] : "";
  while (!data_file.empty() && std::isspace(static_cast<unsigned char>(data_file.back()))) data_file.pop_back();
  if (encoding == "raw" && type && !fields.count("byte skip") && !fields.count("line skip") &&
      (detached ? data_file == "data.raw" : data_file.empty()))
    require(v.domain.volume() * voxel_size(*type) == data_bytes, "NRRD raw data longer or shorter than the sizes");
}

/// What a simple raw-appended .vti holds (fuzz/vtk_xml_oracle.h): arrays tiling the appended data,
/// the loaded array exactly as long as the voxels.
void check_vti(const Volume& v, const std::string& file) {
  // The Spacing attribute, when it is plain (no Direction to scale it): finite, non-zero, kept as
  // the voxel size (NaN, 0 and inf once became 1).
  const std::string spacing = isocurv::fuzz::xml_attribute(file, "ImageData", "Spacing");
  if (!spacing.empty() && isocurv::fuzz::xml_attribute(file, "ImageData", "Direction").empty() &&
      file.find("Spacing=") == file.rfind("Spacing=") && file.find("<!") == std::string::npos &&
      file.find("<ImageData ") == file.rfind("<ImageData ")) {  // one plain ImageData tag, no comments
    const char* p = spacing.c_str();
    double s[3];
    int n = 0;
    for (; n < 3; ++n) {
      char* end = nullptr;
      s[n] = std::strtod(p, &end);
      if (end == p) break;
      p = end;
    }
    if (n == 3 && *p == '\0')
      for (int i = 0; i < 3; ++i) {
        require(std::isfinite(s[i]) && s[i] != 0, "a NaN, infinite or zero .vti Spacing loaded");
        require(std::fabs(v.spacing()[i] - std::fabs(s[i])) <= 1e-9 * std::fabs(s[i]), ".vti Spacing not kept");
      }
  }
  bool applies = false;
  std::string problem;
  const auto arrays = raw_appended_arrays(file, applies, problem);
  if (!applies) return;
  require(problem.empty(), "a .vti whose appended arrays do not tile its data loaded: " + problem);
  const RawArray* used = nullptr;
  int named = 0;
  for (const auto& a : arrays)
    if (a.section == "PointData" && a.name == v.grid_name && named++ == 0) used = &a;
  if (named == 1)  // the array loaded, when its name says which one it was
    require(used->bytes == v.domain.volume() * type_bytes(used->type), "the .vti array's bytes are not the voxels'");
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
    const std::string text(reinterpret_cast<const char*>(data), size);
    if (kFormat == "nrrd") {
      check_nrrd(v, text, 0, false);
    } else if (kFormat == "nhdr") {
      const std::size_t split = text.find(kSplit);
      if (split != std::string::npos)
        check_nrrd(v, text.substr(0, split) + "\n", size - split - kSplit.size(), true);
    } else if (kFormat == "vti") {
      check_vti(v, text);
    }
  } catch (const isocurv::Error&) {
    // the one allowed failure
  }
  return 0;
}
