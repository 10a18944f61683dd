// NRRD (.nrrd with attached data, .nhdr with a detached data file): 3-D scalar images with raw,
// gzip or ASCII encoding; geometry from "space directions" + "space origin", else "spacings";
// the anatomical meaning of the world axes from "space" (Volume::world_space). Both `spacings`
// and `space directions` given must agree; `line skip` is 0 or more; integer fields are written
// as integers (header_text.h).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "core/error.h"
#include "volume/dense_image.h"
#include "volume/file_bytes.h"
#include "volume/header_text.h"
#include "volume/loaders.h"

namespace isocurv::volume {
namespace {

std::optional<VoxelType> nrrd_type(const std::string& t) {
  static const std::map<std::string, VoxelType> types{
      {"signed char", VoxelType::Int8},        {"int8", VoxelType::Int8},
      {"int8_t", VoxelType::Int8},             {"uchar", VoxelType::UInt8},
      {"unsigned char", VoxelType::UInt8},     {"uint8", VoxelType::UInt8},
      {"uint8_t", VoxelType::UInt8},           {"short", VoxelType::Int16},
      {"short int", VoxelType::Int16},         {"signed short", VoxelType::Int16},
      {"signed short int", VoxelType::Int16},  {"int16", VoxelType::Int16},
      {"int16_t", VoxelType::Int16},           {"ushort", VoxelType::UInt16},
      {"unsigned short", VoxelType::UInt16},   {"unsigned short int", VoxelType::UInt16},
      {"uint16", VoxelType::UInt16},           {"uint16_t", VoxelType::UInt16},
      {"int", VoxelType::Int32},               {"signed int", VoxelType::Int32},
      {"int32", VoxelType::Int32},             {"int32_t", VoxelType::Int32},
      {"uint", VoxelType::UInt32},             {"unsigned int", VoxelType::UInt32},
      {"uint32", VoxelType::UInt32},           {"uint32_t", VoxelType::UInt32},
      {"float", VoxelType::Float32},           {"double", VoxelType::Float64}};
  const auto it = types.find(to_lower(t));
  if (it == types.end()) return std::nullopt;
  return it->second;
}

/// "(1,0,0)" -> {1,0,0}; nullopt for "none" or anything else.
std::optional<std::array<double, 3>> parse_vector(const std::string& s) {
  std::string t = trim(s);
  if (t.size() < 2 || t.front() != '(' || t.back() != ')') return std::nullopt;
  t = t.substr(1, t.size() - 2);
  std::replace(t.begin(), t.end(), ',', ' ');
  const auto v = parse_numbers(t);
  if (!v || v->size() != 3) return std::nullopt;
  return std::array<double, 3>{(*v)[0], (*v)[1], (*v)[2]};
}

/// Splits "(a,b,c) (d,e,f) none" into its vector tokens.
std::vector<std::string> vector_tokens(const std::string& s) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i >= s.size()) break;
    std::size_t j = i;
    if (s[i] == '(') {
      j = s.find(')', i);
      j = j == std::string::npos ? s.size() : j + 1;
    } else {
      while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
    }
    out.push_back(s.substr(i, j - i));
    i = j;
  }
  return out;
}

/// NRRD's `space` (any case, full name or abbreviation) as the letters of +x +y +z ("RAS",
/// "LAS", "LPS"), empty for the non-anatomical 3-D spaces; throws for a time space or an unknown
/// name.
std::string world_space_of(const std::string& path, const std::string& space) {
  const std::string s = to_lower(space);
  if (s == "right-anterior-superior" || s == "ras") return "RAS";
  if (s == "left-anterior-superior" || s == "las") return "LAS";
  if (s == "left-posterior-superior" || s == "lps") return "LPS";
  if (s == "scanner-xyz" || s == "3d-right-handed" || s == "3d-left-handed") return "";
  if ((s.size() > 5 && s.compare(s.size() - 5, 5, "-time") == 0) || s == "rast" || s == "last" ||
      s == "lpst")
    throw Error(path, "NRRD space '" + space + "' has a time axis; only 3-D spaces are supported");
  throw Error(path, "unknown NRRD space '" + space +
                        "' (expected right-anterior-superior, left-anterior-superior, "
                        "left-posterior-superior, scanner-xyz, 3D-right-handed or 3D-left-handed)");
}

}  // namespace

Volume load_nrrd(const std::string& path, const LoadOptions& options) {
  const std::uint64_t size = file_size(path);
  const Bytes head = read_bytes(path, 0, std::min<std::uint64_t>(size, 1 << 16));
  if (head.size() < 8 || std::memcmp(head.data(), "NRRD000", 7) != 0) throw Error(path, "not a NRRD file (no NRRD000x magic)");

  std::map<std::string, std::string> fields;
  std::size_t pos = 0;
  bool first = true, header_done = false;
  while (pos < head.size()) {
    const auto* nl = static_cast<const std::uint8_t*>(std::memchr(head.data() + pos, '\n', head.size() - pos));
    if (!nl) break;
    const std::size_t end = std::size_t(nl - head.data());
    std::string line(head.begin() + long(pos), head.begin() + long(end));
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (first) {
      first = false;
      continue;  // magic line
    }
    if (line.empty()) {
      header_done = true;
      break;
    }
    if (line[0] == '#') continue;
    if (line.find(":=") != std::string::npos) continue;  // key/value pairs carry no geometry
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) throw Error(path, "bad NRRD header line '" + line.substr(0, 60) + "'");
    std::string key = to_lower(trim(line.substr(0, colon)));
    if (key == "datafile") key = "data file";  // one field, two spellings
    // A field given twice is ambiguous (a second `sizes:` once silently won): refused.
    if (!fields.emplace(key, trim(line.substr(colon + 2))).second)
      throw Error(path, "NRRD field '" + key + "' is given twice");
  }
  auto get = [&](const std::string& k) -> std::string { return fields.count(k) ? fields[k] : std::string(); };
  const std::string data_file = get("data file");
  if (!header_done && data_file.empty()) throw Error(path, "NRRD header is not terminated by a blank line");

  if (get("dimension") != "3") throw Error(path, "only 3-D NRRD images are supported (dimension: " + get("dimension") + ")");
  if (!fields.count("sizes")) throw Error(path, "NRRD header has no sizes");
  const auto d = parse_integers_exact(path, get("sizes"), 3, "sizes");
  const auto type = nrrd_type(get("type"));
  if (!type) throw Error(path, "unsupported NRRD type '" + get("type") + "'");
  const std::string encoding = to_lower(get("encoding"));
  const bool gzip = encoding == "gzip" || encoding == "gz";
  const bool ascii = encoding == "ascii" || encoding == "text" || encoding == "txt";
  if (!gzip && !ascii && encoding != "raw") throw Error(path, "unsupported NRRD encoding '" + encoding + "'");
  const std::string endian = to_lower(get("endian"));
  if (voxel_size(*type) > 1 && !ascii && endian != "little" && endian != "big")
    throw Error(path, "NRRD header has no valid endian field");
  const bool big_endian = endian == "big";

  const std::string world_space = fields.count("space") ? world_space_of(path, get("space")) : "";
  DenseImage image;
  if (fields.count("space directions")) {
    const auto tokens = vector_tokens(get("space directions"));
    if (tokens.size() != 3) throw Error(path, "bad space directions '" + get("space directions") + "'");
    for (std::size_t i = 0; i < 3; ++i) {
      const auto v = parse_vector(tokens[i]);
      if (!v) throw Error(path, "bad space directions '" + get("space directions") + "'");
      const double len = std::sqrt((*v)[0] * (*v)[0] + (*v)[1] * (*v)[1] + (*v)[2] * (*v)[2]);
      if (!(len > 0)) throw Error(path, "zero-length space direction " + tokens[i]);
      image.spacing[i] = len;
      for (std::size_t j = 0; j < 3; ++j) image.axes[i][j] = (*v)[j] / len;
    }
    // `spacings` beside `space directions`: NRRD (teem) forbids the pair. Given equal (as some
    // writers repeat them) or as nan (teem's "not set"), it is read; when they disagree nothing
    // says which one is right (the spacing of an axis would silently be the directions'), so the
    // file is refused, naming both. A negative spacing disagrees too: the direction gives the sign.
    if (fields.count("spacings")) {
      const auto s = parse_numbers_exact(path, get("spacings"), 3, "spacings");
      for (std::size_t i = 0; i < 3; ++i) {
        if (std::isnan(s[i])) continue;
        if (!(std::fabs(s[i] - image.spacing[i]) <= 1e-6 * image.spacing[i])) {
          char text[96];
          std::snprintf(text, sizeof text, " (axis %c: %g against %g)", char('x' + i), s[i], image.spacing[i]);
          throw Error(path, "NRRD spacings '" + get("spacings") + "' disagree with space directions '" +
                                get("space directions") + "'" + text + "; give one of them");
        }
      }
    }
  } else if (fields.count("spacings")) {
    // Kept as written: finish_dense refuses 0 and non-finite spacings (NaN once became 1) and
    // takes a negative one as a flip, as every format does.
    const auto s = parse_numbers_exact(path, get("spacings"), 3, "spacings");
    for (std::size_t i = 0; i < 3; ++i) image.spacing[i] = s[i];
  }
  if (fields.count("space origin")) {
    const auto o = parse_vector(get("space origin"));
    if (!o) throw Error(path, "bad space origin '" + get("space origin") + "'");
    image.origin = *o;
  }

  // Payload: after the blank line, or in the detached data file.
  std::string data_path = path;
  std::uint64_t data_offset = pos;
  if (!data_file.empty()) {
    if (data_file.rfind("LIST", 0) == 0 || data_file.find('%') != std::string::npos ||
        vector_tokens(data_file).size() != 1)
      throw Error(path, "unsupported data file '" + data_file + "' (a single data file is needed)");
    const std::string dir = directory_of(path);
    data_path = (data_file[0] == '/' || dir.empty()) ? data_file : dir + "/" + data_file;
    data_offset = 0;
    try {
      file_size(data_path);
    } catch (const Error&) {
      throw Error(path, "data file '" + data_path + "' not found");
    }
  }
  const std::uint64_t data_size = file_size(data_path);
  if (data_offset > data_size) throw Error(data_path, "voxel data is missing");
  // line skip, then byte skip (-1: the data ends the file; raw encoding only).
  if (fields.count("line skip")) {
    const long long lines = parse_integers_exact(path, get("line skip"), 1, "line skip")[0];
    // Only `byte skip` has a -1 (the data end the file); a negative line count means nothing, and
    // was once read as 0: refused.
    if (lines < 0) throw Error(path, "bad line skip '" + get("line skip") + "' (a number of lines, 0 or more)");
    const Bytes text = read_bytes(data_path, data_offset, std::min<std::uint64_t>(data_size - data_offset, 1 << 20));
    std::size_t p = 0;
    for (long long i = 0; i < lines; ++i) {
      // An empty payload has no buffer at all: memchr must not see its null pointer (UBSan, found
      // by the nrrd fuzzer: `line skip: 1` before no data).
      if (p >= text.size()) throw Error(data_path, "line skip runs past the data");
      const auto* nl = static_cast<const std::uint8_t*>(std::memchr(text.data() + p, '\n', text.size() - p));
      if (!nl) throw Error(data_path, "line skip runs past the data");
      p = std::size_t(nl - text.data()) + 1;
    }
    data_offset += p;
  }
  long long byte_skip = fields.count("byte skip") ? parse_integers_exact(path, get("byte skip"), 1, "byte skip")[0] : 0;
  if (byte_skip < -1) throw Error(path, "bad byte skip");
  // The sizes must fit the data before anything is allocated for them.
  const std::uint64_t after_skip = data_size - data_offset - std::min<std::uint64_t>(
      data_size - data_offset, byte_skip > 0 && !ascii && !gzip ? std::uint64_t(byte_skip) : 0);
  const std::uint64_t count = checked_payload(path, {d[0], d[1], d[2]}, *type, data_path, after_skip,
                                              ascii ? Payload::Ascii : gzip ? Payload::Compressed : Payload::Raw);
  image.dims = {int(d[0]), int(d[1]), int(d[2])};
  const std::uint64_t bytes_needed = count * voxel_size(*type);

  if (ascii) {
    const Bytes text = read_bytes(data_path, data_offset, data_size - data_offset);
    const char* b = reinterpret_cast<const char*>(text.data());
    image.values = parse_ascii_voxels(data_path, b, b + text.size(), count);
    image.voxel_type = voxel_type_name(*type);
  } else if (gzip) {
    if (byte_skip < 0) throw Error(path, "byte skip -1 is only valid with raw encoding");
    const Bytes z = read_bytes(data_path, data_offset, data_size - data_offset);
    decode_into(image, inflate_exact(data_path, z.data(), z.size(), bytes_needed + std::uint64_t(byte_skip), "voxel data"),
                std::uint64_t(byte_skip), count, *type, big_endian);
  } else {
    const std::uint64_t available = data_size - data_offset;
    if (byte_skip == -1) byte_skip = available >= bytes_needed ? (long long)(available - bytes_needed) : 0;
    if (byte_skip < 0) throw Error(path, "bad byte skip");
    if (available < std::uint64_t(byte_skip) + bytes_needed)
      throw Error(data_path, "voxel data is truncated: " + std::to_string(available) + " bytes, the header's " +
                                 std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) +
                                 " " + voxel_type_name(*type) + " needs " + std::to_string(bytes_needed));
    // More data than the sizes need means a wrong header (the grid would silently be smaller),
    // as raw and MetaImage files say too; `byte skip: -1` alone declares leading bytes to skip.
    if (available > std::uint64_t(byte_skip) + bytes_needed)
      throw Error(data_path, "voxel data has " + std::to_string(available - std::uint64_t(byte_skip)) +
                                 " bytes, the header's " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                                 std::to_string(d[2]) + " " + voxel_type_name(*type) + " needs " +
                                 std::to_string(bytes_needed) + " (sizes or type do not match the data)");
    read_uncompressed(image, data_path, data_offset + std::uint64_t(byte_skip), *type, big_endian,
                      options);  // all, or LoadOptions::z_slab
  }
  Volume v = finish_dense(std::move(image), path, "nrrd", options);
  v.world_space = world_space;
  if (fields.count("space units")) {
    // "mm" "mm" "mm": the unit when all three agree and it is a plain word.
    std::vector<std::string> units;
    const std::string su = get("space units");
    for (std::size_t i = 0; i < su.size();) {
      const std::size_t a = su.find('"', i);
      if (a == std::string::npos) break;
      const std::size_t b = su.find('"', a + 1);
      if (b == std::string::npos) break;
      units.push_back(su.substr(a + 1, b - a - 1));
      i = b + 1;
    }
    const bool plain = units.size() == 3 && !units[0].empty() && units[0].size() <= 8 &&
                       std::all_of(units[0].begin(), units[0].end(),
                                   [](unsigned char c) { return std::isalpha(c) != 0; });
    if (plain && units[1] == units[0] && units[2] == units[0]) v.length_unit = units[0];
  }
  return v;
}

}  // namespace isocurv::volume
