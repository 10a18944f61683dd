// MetaImage (.mhd header + data file, or .mha with the data after the header): `Key = Value`
// lines ending with ElementDataFile; raw, zlib-compressed (CompressedData = True; a file shorter
// than its CompressedDataSize is refused) or ASCII data.
// Raw binary data honour LoadOptions::z_slab (index z is the file's slice order: nothing here
// permutes or flips the voxels); compressed and ASCII data are read whole.
#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

std::optional<VoxelType> met_type(const std::string& t) {
  static const std::map<std::string, VoxelType> types{
      {"MET_UCHAR", VoxelType::UInt8},   {"MET_CHAR", VoxelType::Int8},    {"MET_USHORT", VoxelType::UInt16},
      {"MET_SHORT", VoxelType::Int16},   {"MET_UINT", VoxelType::UInt32},  {"MET_INT", VoxelType::Int32},
      {"MET_ULONG", VoxelType::UInt32},  {"MET_LONG", VoxelType::Int32},   {"MET_FLOAT", VoxelType::Float32},
      {"MET_DOUBLE", VoxelType::Float64}};
  const auto it = types.find(t);
  if (it == types.end()) return std::nullopt;
  return it->second;
}

bool is_true(const std::string& v) {
  const std::string l = to_lower(v);
  return l == "true" || l == "1" || l == "yes";
}

}  // namespace

Volume load_metaimage(const std::string& path, const LoadOptions& options) {
  const std::uint64_t size = file_size(path);
  const Bytes head = read_bytes(path, 0, std::min<std::uint64_t>(size, 1 << 16));

  std::map<std::string, std::string> keys;
  std::size_t pos = 0;
  bool have_data_file = false;
  while (pos < head.size()) {
    const auto* nl = static_cast<const std::uint8_t*>(std::memchr(head.data() + pos, '\n', head.size() - pos));
    const std::size_t end = nl ? std::size_t(nl - head.data()) : head.size();
    const std::string line = trim(std::string(head.begin() + long(pos), head.begin() + long(end)));
    pos = nl ? end + 1 : end;
    if (line.empty() || line[0] == '#') continue;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) throw Error(path, "bad MetaImage header line '" + line.substr(0, 60) + "'");
    const std::string key = trim(line.substr(0, eq));
    keys[key] = trim(line.substr(eq + 1));
    if (key == "ElementDataFile") {
      have_data_file = true;
      break;
    }
  }
  if (!have_data_file) throw Error(path, "MetaImage header has no ElementDataFile");
  auto get = [&](const std::string& k) -> std::string { return keys.count(k) ? keys[k] : std::string(); };

  if (keys.count("NDims") && parse_integers_exact(path, keys["NDims"], 1, "NDims")[0] != 3)
    throw Error(path, "only 3-D images are supported (NDims = " + keys["NDims"] + ")");
  if (!keys.count("DimSize")) throw Error(path, "MetaImage header has no DimSize");
  const auto d = parse_integers_exact(path, keys["DimSize"], 3, "DimSize");
  if (keys.count("ElementNumberOfChannels") &&
      parse_integers_exact(path, keys["ElementNumberOfChannels"], 1, "ElementNumberOfChannels")[0] != 1)
    throw Error(path, "only single-channel images are supported");
  const auto type = met_type(get("ElementType"));
  if (!type) throw Error(path, "unsupported MetaImage ElementType '" + get("ElementType") + "'");
  const bool msb = is_true(keys.count("ElementByteOrderMSB") ? get("ElementByteOrderMSB") : get("BinaryDataByteOrderMSB"));
  const bool compressed = is_true(get("CompressedData"));
  const bool binary = !keys.count("BinaryData") || is_true(get("BinaryData"));

  DenseImage image;
  for (const char* k : {"ElementSpacing", "ElementSize"})
    if (keys.count(k)) {
      const auto s = parse_numbers_exact(path, keys[k], 3, k);
      image.spacing = {s[0], s[1], s[2]};
      break;
    }
  for (const char* k : {"Offset", "Origin", "Position"})
    if (keys.count(k)) {
      const auto o = parse_numbers_exact(path, keys[k], 3, k);
      image.origin = {o[0], o[1], o[2]};
      break;
    }
  for (const char* k : {"TransformMatrix", "Rotation", "Orientation"})
    if (keys.count(k)) {
      // Consecutive triples are the world directions of the index axes (as ITK reads them).
      const auto m = parse_numbers_exact(path, keys[k], 9, k);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) image.axes[std::size_t(i)][std::size_t(j)] = m[std::size_t(3 * i + j)];
      break;
    }

  // Locate the payload.
  const std::string data_file = get("ElementDataFile");
  std::string data_path = path;
  std::uint64_t data_offset = pos;
  if (data_file != "LOCAL") {
    if (data_file.empty() || data_file == "LIST" || data_file.find('%') != std::string::npos ||
        data_file.find(' ') != std::string::npos)
      throw Error(path, "unsupported ElementDataFile '" + data_file + "' (a single data file or LOCAL is needed)");
    const std::string dir = directory_of(path);
    data_path = dir.empty() ? data_file : dir + "/" + data_file;
    data_offset = 0;
    if (!std::ifstream(data_path).good()) throw Error(path, "data file '" + data_path + "' not found");
  }
  const std::uint64_t data_size = file_size(data_path);
  if (data_offset > data_size) throw Error(data_path, "voxel data is missing");
  long long skip = 0;
  if (keys.count("HeaderSize")) {
    skip = parse_integers_exact(path, keys["HeaderSize"], 1, "HeaderSize")[0];
    if (skip < -1) throw Error(path, "bad HeaderSize " + keys["HeaderSize"]);
    if (skip > 0) data_offset = std::min(data_size, data_offset + std::uint64_t(std::min(skip, 1LL << 62)));
  }
  // CompressedDataSize (optional) is checked against the compressed bytes present; it was once
  // ignored. Fewer bytes than it says: the file is cut, refused (one line naming the field). More
  // bytes than it says: read, without a warning, because the zlib stream itself decides where the
  // data end and its Adler-32 trailer and exact inflated size vouch for them (inflate_exact), and
  // files in the wild carry a stale count (VTK's frogtissue.mhd says 260020 for a 262087-byte
  // stream that inflates exactly to its DimSize, checksum correct).
  if (compressed && binary && keys.count("CompressedDataSize")) {
    const long long declared = parse_integers_exact(path, keys["CompressedDataSize"], 1, "CompressedDataSize")[0];
    if (declared < 1) throw Error(path, "bad CompressedDataSize '" + keys["CompressedDataSize"] + "'");
    const std::uint64_t present = data_size - data_offset;
    if (std::uint64_t(declared) > present)
      throw Error(data_path, "voxel data is truncated: CompressedDataSize " + std::to_string(declared) +
                                 " but the file holds " + std::to_string(present) + " compressed bytes");
  }
  // The dimensions must fit the data before anything is allocated for them.
  const std::uint64_t count = checked_payload(path, {d[0], d[1], d[2]}, *type, data_path, data_size - data_offset,
                                              !binary ? Payload::Ascii : compressed ? Payload::Compressed : Payload::Raw);
  image.dims = {int(d[0]), int(d[1]), int(d[2])};
  const std::uint64_t bytes_needed = count * voxel_size(*type);
  if (skip == -1 && !compressed && binary) data_offset = data_size - bytes_needed;
  const std::uint64_t available = data_size - data_offset;

  if (!binary) {
    const Bytes text = read_bytes(data_path, data_offset, available);
    const char* b = reinterpret_cast<const char*>(text.data());
    image.values = parse_ascii_voxels(data_path, b, b + text.size(), count);
    image.voxel_type = voxel_type_name(*type);
  } else if (compressed) {
    const Bytes z = read_bytes(data_path, data_offset, available);
    decode_into(image, inflate_exact(data_path, z.data(), z.size(), bytes_needed, "voxel data"), 0, count, *type, msb);
  } else {
    if (available < bytes_needed)
      throw Error(data_path, "voxel data is truncated: " + std::to_string(available) + " bytes, the header's " +
                                 std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) +
                                 " " + voxel_type_name(*type) + " needs " + std::to_string(bytes_needed));
    if (data_path != path && data_offset == 0 && available > bytes_needed)
      throw Error(data_path, "data file has " + std::to_string(available) + " bytes, the header's dimensions need " +
                                 std::to_string(bytes_needed));
    read_uncompressed(image, data_path, data_offset, *type, msb, options);  // all, or LoadOptions::z_slab
  }
  Volume v = finish_dense(std::move(image), path, "metaimage", options);
  v.world_space = "LPS";
  v.length_unit = "mm";  // MetaIO has no unit field; ElementSpacing is in millimetres by convention
  return v;
}

}  // namespace isocurv::volume
