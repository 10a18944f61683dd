// DGtal VOL files: ASCII `Key: value` lines, a line holding only ".", then X*Y*Z uint8 voxels,
// x fastest: raw for Version 2, a zlib stream for Version 3.
#include <algorithm>
#include <cstring>
#include <map>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {

Volume load_dgtal_vol(const std::string& path, const LoadOptions& options) {
  const std::uint64_t size = file_size(path);
  Bytes file = read_bytes(path, 0, size);

  // Header: lines up to the "." terminator (at most 64 KiB of text).
  std::map<std::string, std::string> keys;
  std::size_t pos = 0;
  bool terminated = false;
  while (pos < file.size() && pos < (1u << 16)) {
    const auto* nl = static_cast<const std::uint8_t*>(std::memchr(file.data() + pos, '\n', file.size() - pos));
    const std::size_t end = nl ? std::size_t(nl - file.data()) : file.size();
    const std::string line = trim(std::string(file.begin() + long(pos), file.begin() + long(end)));
    pos = end + 1;
    if (line == ".") {
      terminated = true;
      break;
    }
    if (line.empty()) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) throw Error(path, "bad VOL header line '" + line.substr(0, 60) + "'");
    keys[trim(line.substr(0, colon))] = trim(line.substr(colon + 1));
  }
  if (!terminated) throw Error(path, "not a VOL file: no header terminator line '.'");
  for (const char* k : {"X", "Y", "Z"})
    if (!keys.count(k)) throw Error(path, std::string("VOL header has no '") + k + "' size");
  const std::array<long long, 3> dims{parse_integers_exact(path, keys["X"], 1, "X size")[0],
                                      parse_integers_exact(path, keys["Y"], 1, "Y size")[0],
                                      parse_integers_exact(path, keys["Z"], 1, "Z size")[0]};
  const long long version_number =
      keys.count("Version") ? parse_integers_exact(path, keys["Version"], 1, "Version")[0] : 2;
  if (version_number != 2 && version_number != 3)
    throw Error(path, "unsupported VOL version " + std::to_string(version_number));
  const int version = int(version_number);
  if (keys.count("Voxel-Endian") && keys["Voxel-Endian"] != "0")
    throw Error(path, "unsupported VOL Voxel-Endian '" + keys["Voxel-Endian"] + "' (only 8-bit voxels are read)");

  Bytes voxels;
  pos = std::min(pos, file.size());
  const std::uint8_t* payload = file.data() + pos;
  const std::size_t payload_size = file.size() - pos;
  const std::uint64_t count = checked_payload(path, dims, VoxelType::UInt8, path, payload_size,
                                              version == 3 ? Payload::Compressed : Payload::Raw);
  if (version == 3) {
    voxels = inflate_exact(path, payload, payload_size, count, "voxel data");
  } else if (payload_size != count) {
    throw Error(path, "voxel data has " + std::to_string(payload_size) + " bytes, the header's " + keys["X"] + "x" +
                          keys["Y"] + "x" + keys["Z"] + " needs " + std::to_string(count) +
                          (payload_size < count ? " (truncated)" : ""));
  }

  DenseImage image;
  image.dims = {int(dims[0]), int(dims[1]), int(dims[2])};
  if (keys.count("Voxel-Size")) {
    const double s = parse_numbers_exact(path, keys["Voxel-Size"], 1, "Voxel-Size")[0];
    image.spacing = {s, s, s};  // finish_dense refuses 0 and non-finite, flips a negative one
  }
  if (version == 3)
    decode_into(image, std::move(voxels), 0, count, VoxelType::UInt8, false);
  else
    decode_into(image, std::move(file), pos, count, VoxelType::UInt8, false);
  return finish_dense(std::move(image), path, "dgtal-vol", options);
}

}  // namespace isocurv::volume
