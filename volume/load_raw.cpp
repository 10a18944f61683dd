// Headerless raw volumes (.raw, .bin, and gzip-compressed .raw.gz / .bin-gz): layout from
// LoadOptions::raw, or, for whatever it leaves unset, from a file name such as
// `lobster_301x324x56_uint8.raw` or `headsq_64x64x93_int16le.raw` (`_<X>x<Y>x<Z>_<type>[le|be]`).
#include <filesystem>
#include <regex>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

struct NameLayout {
  std::array<int, 3> dims{0, 0, 0};
  std::string type;
  std::optional<bool> big_endian;
};

NameLayout layout_from_name(const std::string& path) {
  NameLayout out;
  const std::string name = to_lower(std::filesystem::path(path).filename().string());
  static const std::regex re(
      R"(_(\d{1,9})x(\d{1,9})x(\d{1,9})_(uint8|int8|uint16|int16|uint32|int32|float32|float64|float|double)(le|be)?(?=[_.]))");
  std::smatch m;
  if (std::regex_search(name, m, re)) {
    out.dims = {std::stoi(m[1]), std::stoi(m[2]), std::stoi(m[3])};
    out.type = m[4];
    if (m[5].matched) out.big_endian = m[5] == "be";
  }
  return out;
}

}  // namespace

Volume load_raw(const std::string& path, const LoadOptions& options) {
  const RawOptions& raw = options.raw;
  const NameLayout named = layout_from_name(path);
  const bool have_dims = raw.dims[0] != 0 || raw.dims[1] != 0 || raw.dims[2] != 0;
  const std::array<int, 3> dims = have_dims ? raw.dims : named.dims;
  const std::string type_name = raw.type.empty() ? named.type : raw.type;
  // An explicit byte order always wins; the file name's only counts when the layout comes from
  // the name too.
  const bool big_endian = raw.big_endian                                         ? *raw.big_endian
                          : (!have_dims && raw.type.empty() && named.big_endian) ? *named.big_endian
                                                                                 : false;

  if (dims[0] == 0 && dims[1] == 0 && dims[2] == 0)
    throw Error(path, "raw data needs its dimensions (--dims X Y Z); the file name does not carry _<X>x<Y>x<Z>_<type>");
  if (type_name.empty())
    throw Error(path, "raw data needs its voxel type (--type uint8|int8|uint16|int16|uint32|int32|float|double)");
  const auto type = parse_voxel_type(type_name);
  if (!type) throw Error(path, "unsupported voxel type '" + type_name + "'");
  const std::string name = to_lower(path);
  const bool gz = name.size() > 3 && (name.compare(name.size() - 3, 3, ".gz") == 0 ||
                                      name.compare(name.size() - 3, 3, "-gz") == 0);
  // The layout must fit the file before anything is allocated for it.
  const std::uint64_t count = checked_payload(path, {dims[0], dims[1], dims[2]}, *type, path, file_size(path),
                                              gz ? Payload::Compressed : Payload::Raw, "layout");
  const std::uint64_t bytes_needed = count * voxel_size(*type);
  DenseImage image;
  image.dims = dims;
  image.spacing = raw.spacing;
  image.origin = raw.origin;
  if (gz) {
    decode_into(image, read_gzip_exact(path, bytes_needed, "voxel data"), 0, count, *type, big_endian);
  } else {
    const std::uint64_t size = file_size(path);
    if (size != bytes_needed)
      throw Error(path, "file size " + std::to_string(size) + " does not match " + std::to_string(dims[0]) + "x" +
                            std::to_string(dims[1]) + "x" + std::to_string(dims[2]) + " " + type_name + " (" +
                            std::to_string(bytes_needed) + " bytes)");
    read_uncompressed(image, path, 0, *type, big_endian, options);  // all, or LoadOptions::z_slab
  }
  return finish_dense(std::move(image), path, "raw", options);
}

}  // namespace isocurv::volume
