// Zarr v2 / v3 metadata and OME-NGFF multiscales (zarr_metadata.h).
#include "volume/detail/zarr_metadata.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>

#include "core/error.h"
#include "volume/file_bytes.h"

namespace isocurv::volume::zarr_detail {
namespace {

using json = nlohmann::json;
namespace fs = std::filesystem;

bool zarr_file_exists(const std::string& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string zarr_join(const std::string& dir, const std::string& name) {
  if (dir.empty()) return name;
  return dir.back() == '/' ? dir + name : dir + "/" + name;
}

/// The JSON document in `path` (at most 64 MiB); malformed text is an Error naming it.
json read_json(const std::string& path) {
  const std::uint64_t size = file_size(path);
  if (size > (64u << 20)) throw Error(path, "Zarr metadata file is larger than 64 MiB");
  const Bytes bytes = read_bytes(path, 0, size);
  const char* b = reinterpret_cast<const char*>(bytes.data());
  json j = json::parse(b, b + bytes.size(), nullptr, false);
  if (j.is_discarded()) throw Error(path, "malformed JSON in Zarr metadata");
  if (!j.is_object()) throw Error(path, "Zarr metadata is not a JSON object");
  return j;
}

const json& member(const std::string& path, const json& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end()) throw Error(path, std::string("Zarr metadata has no \"") + key + "\"");
  return *it;
}

std::vector<long long> shape_of(const std::string& path, const json& j, const char* what, bool allow_zero) {
  if (!j.is_array() || j.empty()) throw Error(path, std::string("Zarr \"") + what + "\" is not a list of integers");
  std::vector<long long> out;
  for (const auto& v : j) {
    if (!v.is_number_integer()) throw Error(path, std::string("Zarr \"") + what + "\" is not a list of integers");
    const long long n = v.get<long long>();
    if (n < (allow_zero ? 0 : 1))
      throw Error(path, std::string("Zarr \"") + what + "\" holds " + std::to_string(n) +
                            (allow_zero ? " (sizes are 0 or more)" : " (sizes are 1 or more)"));
    out.push_back(n);
  }
  if (out.size() > 32) throw Error(path, "Zarr arrays of more than 32 dimensions are not supported");
  return out;
}

/// The product of `dims` times `item`, or throws when it exceeds `limit`.
std::uint64_t checked_product(const std::string& path, const std::vector<long long>& dims, std::uint64_t item,
                              std::uint64_t limit, const std::string& what) {
  std::uint64_t p = item;
  for (const long long d : dims) {
    if (d == 0) return 0;
    if (std::uint64_t(d) > limit / p) throw Error(path, what);
    p *= std::uint64_t(d);
  }
  return p;
}

VoxelType v3_type(const std::string& path, const json& j) {
  if (!j.is_string()) throw Error(path, "Zarr data_type is not a name (extension data types are not supported)");
  static const std::map<std::string, VoxelType> types{
      {"uint8", VoxelType::UInt8},   {"int8", VoxelType::Int8},     {"uint16", VoxelType::UInt16},
      {"int16", VoxelType::Int16},   {"uint32", VoxelType::UInt32}, {"int32", VoxelType::Int32},
      {"float32", VoxelType::Float32}, {"float64", VoxelType::Float64}};
  const auto it = types.find(j.get<std::string>());
  if (it == types.end())
    throw Error(path, "Zarr data type '" + j.get<std::string>() +
                          "' is not supported (uint8 int8 uint16 int16 uint32 int32 float32 float64)");
  return it->second;
}

/// "<u2" -> uint16 little-endian.
VoxelType v2_type(const std::string& path, const json& j, bool& big_endian) {
  if (!j.is_string()) throw Error(path, "Zarr dtype is not a simple type (structured dtypes are not supported)");
  const std::string d = j.get<std::string>();
  static const std::map<std::string, VoxelType> types{
      {"u1", VoxelType::UInt8},   {"i1", VoxelType::Int8},     {"u2", VoxelType::UInt16},
      {"i2", VoxelType::Int16},   {"u4", VoxelType::UInt32},   {"i4", VoxelType::Int32},
      {"f4", VoxelType::Float32}, {"f8", VoxelType::Float64}};
  const auto it = d.size() == 3 ? types.find(d.substr(1)) : types.end();
  if ((d.empty() || (d[0] != '<' && d[0] != '>' && d[0] != '|')) || it == types.end())
    throw Error(path, "Zarr dtype '" + d + "' is not supported (u1 i1 u2 i2 u4 i4 f4 f8 with < > or |)");
  if (d[0] == '|' && voxel_size(it->second) > 1)
    throw Error(path, "Zarr dtype '" + d + "' has no byte order ('|' is for one-byte types)");
  big_endian = d[0] == '>';
  return it->second;
}

double fill_of(const std::string& path, const json& j, VoxelType type) {
  if (j.is_null()) return 0;
  if (j.is_number()) return j.get<double>();
  if (j.is_boolean()) return j.get<bool>() ? 1 : 0;
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "NaN") return std::numeric_limits<double>::quiet_NaN();
    if (s == "Infinity") return std::numeric_limits<double>::infinity();
    if (s == "-Infinity") return -std::numeric_limits<double>::infinity();
    if (s.size() > 2 && s[0] == '0' && s[1] == 'x' && (type == VoxelType::Float32 || type == VoxelType::Float64)) {
      const std::string hex = s.substr(2);
      if (hex.size() == 8 && type == VoxelType::Float32) {
        const std::uint32_t bits = std::uint32_t(std::stoul(hex, nullptr, 16));
        float f;
        std::memcpy(&f, &bits, 4);
        return f;
      }
      if (hex.size() == 16 && type == VoxelType::Float64) {
        const std::uint64_t bits = std::stoull(hex, nullptr, 16);
        double f;
        std::memcpy(&f, &bits, 8);
        return f;
      }
    }
  }
  throw Error(path, "Zarr fill_value '" + j.dump() + "' is not a number, \"NaN\", \"Infinity\" or null");
}

Codec v2_compressor(const std::string& path, const json& c) {
  if (!c.is_object()) throw Error(path, "Zarr compressor is not an object or null");
  const json& id = member(path, c, "id");
  if (!id.is_string()) throw Error(path, "Zarr compressor id is not a string");
  Codec k;
  k.name = id.get<std::string>();
  if (k.name == "zlib") k.kind = Codec::Kind::Zlib;
  else if (k.name == "gzip") k.kind = Codec::Kind::Gzip;
  else if (k.name == "zstd") k.kind = Codec::Kind::Zstd;
  else if (k.name == "blosc") {
    k.kind = Codec::Kind::Blosc;
    if (c.contains("cname") && c["cname"].is_string()) k.name = "blosc(" + c["cname"].get<std::string>() + ")";
  } else
    throw Error(path, "unknown Zarr compressor '" + k.name + "' (supported: zlib gzip zstd blosc)");
  return k;
}

std::vector<Codec> v3_codecs(const std::string& path, const json& list, std::size_t ndim, int depth);

Codec v3_codec(const std::string& path, const json& c, std::size_t ndim, int depth) {
  std::string name;
  json config = json::object();
  if (c.is_string()) {
    name = c.get<std::string>();
  } else if (c.is_object() && c.contains("name") && c["name"].is_string()) {
    name = c["name"].get<std::string>();
    if (c.contains("configuration")) config = c["configuration"];
    if (!config.is_object()) throw Error(path, "Zarr codec '" + name + "' has a configuration that is not an object");
  } else {
    throw Error(path, "Zarr codec entry is not {\"name\": ..., \"configuration\": ...}");
  }
  Codec k;
  k.name = name;
  if (name == "bytes" || name == "endian") {
    k.kind = Codec::Kind::Bytes;
    const std::string e = config.contains("endian") && config["endian"].is_string() ? config["endian"].get<std::string>() : "little";
    if (e != "little" && e != "big") throw Error(path, "Zarr bytes codec endian '" + e + "' is not little or big");
    k.big_endian = e == "big";
    k.name = "bytes(" + e + ")";
  } else if (name == "transpose") {
    k.kind = Codec::Kind::Transpose;
    const json order = config.contains("order") ? config["order"] : json();
    if (order.is_string() && (order == "C" || order == "F")) {
      for (std::size_t i = 0; i < ndim; ++i) k.order.push_back(order == "C" ? int(i) : int(ndim - 1 - i));
    } else if (order.is_array()) {
      for (const auto& v : order) {
        if (!v.is_number_integer()) throw Error(path, "Zarr transpose order is not a list of integers");
        k.order.push_back(v.get<int>());
      }
    }
    std::vector<int> sorted = k.order;
    std::sort(sorted.begin(), sorted.end());
    bool perm = sorted.size() == ndim;
    for (std::size_t i = 0; perm && i < ndim; ++i) perm = sorted[i] == int(i);
    if (!perm) throw Error(path, "Zarr transpose order '" + order.dump() + "' is not a permutation of the dimensions");
    std::string t = "transpose(";
    for (std::size_t i = 0; i < k.order.size(); ++i) t += (i ? "," : "") + std::to_string(k.order[i]);
    k.name = t + ")";
  } else if (name == "gzip") {
    k.kind = Codec::Kind::Gzip;
  } else if (name == "zstd") {
    k.kind = Codec::Kind::Zstd;
  } else if (name == "blosc") {
    k.kind = Codec::Kind::Blosc;
    if (config.contains("cname") && config["cname"].is_string()) k.name = "blosc(" + config["cname"].get<std::string>() + ")";
  } else if (name == "crc32c") {
    k.kind = Codec::Kind::Crc32c;
  } else if (name == "sharding_indexed") {
    if (depth > 3) throw Error(path, "Zarr sharding nested more than 3 deep");
    k.kind = Codec::Kind::Sharding;
    k.inner_chunks = shape_of(path, member(path, config, "chunk_shape"), "chunk_shape", false);
    if (k.inner_chunks.size() != ndim) throw Error(path, "Zarr sharding chunk_shape has the wrong number of dimensions");
    k.inner = v3_codecs(path, member(path, config, "codecs"), ndim, depth + 1);
    if (config.contains("index_codecs")) {
      k.index_codecs = v3_codecs(path, config["index_codecs"], ndim, depth + 1);
    } else {
      Codec b;
      b.name = "bytes(little)";
      k.index_codecs = {b};
    }
    for (const Codec& ic : k.index_codecs)
      if (ic.kind != Codec::Kind::Bytes && ic.kind != Codec::Kind::Crc32c)
        throw Error(path, "Zarr shard index codec '" + ic.name + "' is not supported (bytes and crc32c are)");
    const std::string loc = config.contains("index_location") && config["index_location"].is_string()
                                ? config["index_location"].get<std::string>() : "end";
    if (loc != "end" && loc != "start") throw Error(path, "Zarr shard index_location '" + loc + "' is not start or end");
    k.index_at_end = loc == "end";
    std::string t = "sharding_indexed(chunks ";
    for (std::size_t i = 0; i < k.inner_chunks.size(); ++i) t += (i ? "x" : "") + std::to_string(k.inner_chunks[i]);
    k.name = t + ": " + codecs_text(k.inner) + ")";
  } else {
    throw Error(path, "unknown Zarr codec '" + name +
                          "' (supported: bytes transpose gzip zstd blosc crc32c sharding_indexed)");
  }
  return k;
}

std::vector<Codec> v3_codecs(const std::string& path, const json& list, std::size_t ndim, int depth) {
  if (!list.is_array()) throw Error(path, "Zarr codecs is not a list");
  std::vector<Codec> out;
  for (const auto& c : list) out.push_back(v3_codec(path, c, ndim, depth));
  // Array -> array codecs first, then exactly one array -> bytes codec, then bytes -> bytes.
  int stage = 0, array_to_bytes = 0;
  for (const Codec& c : out) {
    const int s = c.kind == Codec::Kind::Transpose ? 0
                  : (c.kind == Codec::Kind::Bytes || c.kind == Codec::Kind::Sharding) ? 1 : 2;
    if (s < stage) throw Error(path, "Zarr codec '" + c.name + "' is out of order (array, then bytes, then compression)");
    if (s == 1) ++array_to_bytes;
    stage = s;
  }
  if (array_to_bytes != 1) throw Error(path, "Zarr codecs need exactly one bytes or sharding_indexed codec");
  for (std::size_t i = 0; i + 1 < out.size(); ++i)
    if (out[i].kind == Codec::Kind::Transpose && out[i + 1].kind == Codec::Kind::Sharding)
      throw Error(path, "a Zarr transpose before sharding_indexed is not supported");
  return out;
}

/// The sizes of a decoded chunk (and of a shard's inner chunks) must stay reasonable.
void check_chunk_sizes(const std::string& path, const std::vector<long long>& chunks, VoxelType type,
                       const std::vector<Codec>& codecs) {
  checked_product(path, chunks, voxel_size(type), std::uint64_t(1) << 31,
                  "Zarr chunk shape is too large (a decoded chunk over 2 GiB)");
  for (const Codec& c : codecs)
    if (c.kind == Codec::Kind::Sharding) {
      for (std::size_t i = 0; i < chunks.size(); ++i)
        if (chunks[i] % c.inner_chunks[i] != 0)
          throw Error(path, "Zarr shard shape is not a multiple of its inner chunk_shape");
      check_chunk_sizes(path, c.inner_chunks, type, c.inner);
    }
}

}  // namespace

std::string codecs_text(const std::vector<Codec>& codecs) {
  std::string t;
  for (auto it = codecs.rbegin(); it != codecs.rend(); ++it) t += (t.empty() ? "" : " <- ") + it->name;
  return t;
}

ArrayMeta read_array_meta(const std::string& dir) {
  ArrayMeta m;
  m.dir = dir;
  const std::string v3 = zarr_join(dir, "zarr.json"), v2 = zarr_join(dir, ".zarray");
  if (zarr_file_exists(v3)) {
    m.meta_path = v3;
    m.zarr_format = 3;
  } else if (zarr_file_exists(v2)) {
    m.meta_path = v2;
  } else {
    throw Error(dir, "no Zarr array here (neither .zarray nor zarr.json)");
  }
  const std::string& p = m.meta_path;
  const json j = read_json(p);
  try {
    if (m.zarr_format == 3) {
      if (member(p, j, "zarr_format") != 3) throw Error(p, "zarr_format is not 3");
      if (member(p, j, "node_type") != "array") throw Error(p, "Zarr node_type is not \"array\"");
      m.shape = shape_of(p, member(p, j, "shape"), "shape", true);
      m.type = v3_type(p, member(p, j, "data_type"));
      const json& grid = member(p, j, "chunk_grid");
      if (!grid.is_object() || grid.value("name", "") != "regular")
        throw Error(p, "Zarr chunk_grid is not \"regular\" (the only grid supported)");
      m.chunks = shape_of(p, member(p, member(p, grid, "configuration"), "chunk_shape"), "chunk_shape", false);
      const json& keys = member(p, j, "chunk_key_encoding");
      const std::string kname = keys.is_object() ? keys.value("name", "") : "";
      if (kname == "default") {
        m.c_prefix = true;
        m.separator = "/";
      } else if (kname == "v2") {
        m.separator = ".";
      } else {
        throw Error(p, "Zarr chunk_key_encoding '" + kname + "' is not supported (default, v2)");
      }
      if (keys.contains("configuration") && keys["configuration"].is_object() &&
          keys["configuration"].contains("separator")) {
        const json& s = keys["configuration"]["separator"];
        if (s != "/" && s != ".") throw Error(p, "Zarr chunk key separator is not \"/\" or \".\"");
        m.separator = s.get<std::string>();
      }
      m.fill = fill_of(p, member(p, j, "fill_value"), m.type);
      m.codecs = v3_codecs(p, member(p, j, "codecs"), m.shape.size(), 0);
      if (j.contains("storage_transformers") && !j["storage_transformers"].empty())
        throw Error(p, "Zarr storage_transformers are not supported");
      if (j.contains("dimension_names") && j["dimension_names"].is_array())
        for (const auto& n : j["dimension_names"]) m.dimension_names.push_back(n.is_string() ? n.get<std::string>() : "");
    } else {
      if (member(p, j, "zarr_format") != 2) throw Error(p, "zarr_format is not 2");
      m.shape = shape_of(p, member(p, j, "shape"), "shape", true);
      m.chunks = shape_of(p, member(p, j, "chunks"), "chunks", false);
      bool big = false;
      m.type = v2_type(p, member(p, j, "dtype"), big);
      m.fill = fill_of(p, member(p, j, "fill_value"), m.type);
      const json& order = member(p, j, "order");
      if (order != "C" && order != "F") throw Error(p, "Zarr order is not \"C\" or \"F\"");
      if (j.contains("filters") && !j["filters"].is_null() && !j["filters"].empty())
        throw Error(p, "Zarr filters are not supported (" + j["filters"].dump().substr(0, 80) + ")");
      if (j.contains("dimension_separator")) {
        const json& s = j["dimension_separator"];
        if (s != "/" && s != ".") throw Error(p, "Zarr dimension_separator is not \"/\" or \".\"");
        m.separator = s.get<std::string>();
      }
      if (order == "F") {  // F order: C order of the reversed dimensions
        Codec t;
        t.kind = Codec::Kind::Transpose;
        t.name = "order F";
        for (std::size_t i = 0; i < m.shape.size(); ++i) t.order.push_back(int(m.shape.size() - 1 - i));
        m.codecs.push_back(t);
      }
      Codec b;
      b.big_endian = big;
      b.name = voxel_size(m.type) == 1 ? "bytes" : big ? "bytes(big)" : "bytes(little)";
      m.codecs.push_back(b);
      const json& comp = member(p, j, "compressor");
      if (!comp.is_null()) m.codecs.push_back(v2_compressor(p, comp));
    }
  } catch (const json::exception& e) {
    throw Error(p, std::string("malformed Zarr metadata: ") + e.what());
  }
  if (m.chunks.size() != m.shape.size())
    throw Error(p, "Zarr chunk shape has " + std::to_string(m.chunks.size()) + " dimensions, the shape " +
                       std::to_string(m.shape.size()));
  checked_product(p, m.shape, 1, std::uint64_t(1) << 50, "Zarr shape is too large (its product overflows)");
  check_chunk_sizes(p, m.chunks, m.type, m.codecs);
  return m;
}

bool looks_like_zarr(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    for (const char* f : {".zarray", ".zattrs", ".zgroup", "zarr.json"})
      if (zarr_file_exists(zarr_join(path, f))) return true;
  std::string p = path;
  while (p.size() > 1 && p.back() == '/') p.pop_back();
  auto ends = [&](const std::string& s) { return p.size() >= s.size() && p.compare(p.size() - s.size(), s.size(), s) == 0; };
  return ends(".zarr") || ends(".ZARR");
}

std::string short_unit(const std::string& unit) {
  static const std::map<std::string, std::string> units{
      {"meter", "m"},          {"centimeter", "cm"}, {"millimeter", "mm"}, {"micrometer", "um"},
      {"nanometer", "nm"},     {"picometer", "pm"},  {"angstrom", "A"},    {"kilometer", "km"},
      {"decimeter", "dm"},     {"foot", "ft"},       {"inch", "in"},       {"mile", "mi"},
      {"yard", "yd"},          {"m", "m"},           {"mm", "mm"},         {"um", "um"},
      {"nm", "nm"},            {"cm", "cm"}};
  const auto it = units.find(unit);
  return it == units.end() ? "" : it->second;
}

namespace {

/// Applies one coordinateTransformations list to (scale, translation): each later transform acts
/// on the result of the earlier ones.
void apply_transforms(const std::string& path, const json& list, std::vector<double>& scale,
                      std::vector<double>& translation) {
  if (list.is_null()) return;
  if (!list.is_array()) throw Error(path, "OME coordinateTransformations is not a list");
  const std::size_t n = scale.size();
  for (const auto& t : list) {
    if (!t.is_object() || !t.contains("type")) throw Error(path, "OME coordinate transformation has no type");
    const std::string type = t["type"].is_string() ? t["type"].get<std::string>() : "";
    if (type == "identity") continue;
    if (type != "scale" && type != "translation")
      throw Error(path, "OME coordinate transformation '" + type + "' is not supported (scale, translation)");
    if (t.contains("path")) throw Error(path, "OME coordinate transformations stored in a path are not supported");
    const json& v = member(path, t, type.c_str());
    if (!v.is_array() || v.size() != n) throw Error(path, "OME " + type + " does not have one number per axis");
    for (std::size_t i = 0; i < n; ++i) {
      if (!v[i].is_number()) throw Error(path, "OME " + type + " is not a list of numbers");
      const double x = v[i].get<double>();
      if (!std::isfinite(x)) throw Error(path, "OME " + type + " holds a non-finite number");
      if (type == "scale") {
        scale[i] *= x;
        translation[i] *= x;
      } else {
        translation[i] += x;
      }
    }
  }
}

void default_axes(Store& s, std::size_t n, const std::vector<std::string>& names) {
  static const char* five[] = {"t", "c", "z", "y", "x"};
  s.axis_names.assign(n, "");
  s.axis_types.assign(n, "");
  s.axis_units.assign(n, "");
  for (std::size_t i = 0; i < n; ++i) {
    // v3 dimension_names are used when they are the OME names; anything else keeps the default.
    std::string name = i < names.size() ? names[i] : "";
    if (name != "x" && name != "y" && name != "z" && name != "t" && name != "c") name = n <= 5 ? five[5 - n + i] : "";
    s.axis_names[i] = name;
    s.axis_types[i] = (name == "x" || name == "y" || name == "z") ? "space"
                      : name == "t" ? "time" : name == "c" ? "channel" : "";
  }
}

/// Fills s.spatial from the axes: three "space" axes, named x y z or else taken in order z y x.
void map_spatial_axes(Store& s, const std::string& path) {
  std::vector<int> space;
  for (std::size_t i = 0; i < s.axis_types.size(); ++i)
    if (s.axis_types[i] == "space") space.push_back(int(i));
  if (space.size() != 3)
    throw Error(path, "Zarr array has " + std::to_string(space.size()) +
                          " spatial axes; isocurv reads volumes with three (z y x, optionally after t and c)");
  std::array<int, 3> byname{-1, -1, -1};
  for (const int i : space) {
    const std::string& n = s.axis_names[std::size_t(i)];
    if (n == "x" || n == "y" || n == "z") byname[std::size_t(n[0] - 'x')] = i;
  }
  if (byname[0] >= 0 && byname[1] >= 0 && byname[2] >= 0)
    s.spatial = byname;
  else
    s.spatial = {space[2], space[1], space[0]};
  std::string unit = s.axis_units[std::size_t(space[0])];
  for (const int i : space)
    if (s.axis_units[std::size_t(i)] != unit) unit.clear();
  s.length_unit = short_unit(unit);
}

}  // namespace

Store read_store(const std::string& path_in) {
  std::string path = path_in;
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  Store s;
  s.path = path;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) throw Error(path, "a Zarr store is a folder; this is not one (or does not exist)");
  const std::string v3 = zarr_join(path, "zarr.json"), zarray = zarr_join(path, ".zarray"),
                    zattrs = zarr_join(path, ".zattrs"), zgroup = zarr_join(path, ".zgroup");
  json attrs;
  std::string attrs_path;
  bool group = false;
  if (zarr_file_exists(v3)) {
    s.zarr_format = 3;
    const json j = read_json(v3);
    const auto nt = j.find("node_type");
    if (nt == j.end() || !nt->is_string()) throw Error(v3, "Zarr metadata has no \"node_type\"");
    group = *nt == "group";
    if (!group && *nt != "array") throw Error(v3, "Zarr node_type '" + nt->get<std::string>() + "' is not array or group");
    if (j.contains("attributes")) attrs = j["attributes"];
    attrs_path = v3;
    if (attrs.is_object() && attrs.contains("ome")) {
      attrs = attrs["ome"];
      if (attrs.is_object() && attrs.contains("version") && attrs["version"].is_string())
        s.ome_version = attrs["version"].get<std::string>();
    }
  } else if (zarr_file_exists(zarray) || zarr_file_exists(zattrs) || zarr_file_exists(zgroup)) {
    group = !zarr_file_exists(zarray);
    if (zarr_file_exists(zattrs)) {
      attrs = read_json(zattrs);
      attrs_path = zattrs;
    }
  } else {
    throw Error(path, "not a Zarr store: the folder holds no .zarray, .zgroup, .zattrs or zarr.json");
  }
  const bool has_ms = attrs.is_object() && attrs.contains("multiscales");
  if (!has_ms) {
    if (group)
      throw Error(path, "a Zarr group without OME-NGFF multiscales metadata; give the folder of one of its arrays");
    Level l;
    l.path = path;
    l.name = ".";
    l.meta = read_array_meta(path);
    const std::size_t n = l.meta.shape.size();
    if (n < 3 || n > 5) throw Error(l.meta.meta_path, "a Zarr array of " + std::to_string(n) +
                                                          " dimensions; isocurv reads 3 (z y x), 4 (c z y x) or 5 (t c z y x)");
    default_axes(s, n, l.meta.dimension_names);
    l.scale.assign(n, 1.0);
    l.translation.assign(n, 0.0);
    s.levels.push_back(std::move(l));
    map_spatial_axes(s, s.levels[0].meta.meta_path);
    return s;
  }
  try {
    const json& ms = attrs["multiscales"];
    if (!ms.is_array() || ms.empty() || !ms[0].is_object())
      throw Error(attrs_path, "OME multiscales is not a list of multiscale objects");
    const json& m = ms[0];
    if (s.ome_version.empty()) s.ome_version = m.contains("version") && m["version"].is_string() ? m["version"].get<std::string>() : "0.4";
    const json& datasets = member(attrs_path, m, "datasets");
    if (!datasets.is_array() || datasets.empty()) throw Error(attrs_path, "OME multiscales has no datasets");
    if (m.contains("axes")) {
      const json& axes = m["axes"];
      if (!axes.is_array()) throw Error(attrs_path, "OME axes is not a list");
      for (const auto& a : axes) {
        if (a.is_string()) {  // 0.3: names only
          const std::string n = a.get<std::string>();
          s.axis_names.push_back(n);
          s.axis_types.push_back((n == "x" || n == "y" || n == "z") ? "space" : n == "t" ? "time" : n == "c" ? "channel" : "");
          s.axis_units.push_back("");
        } else if (a.is_object() && a.contains("name") && a["name"].is_string()) {
          const std::string n = a["name"].get<std::string>();
          s.axis_names.push_back(n);
          std::string type = a.contains("type") && a["type"].is_string() ? a["type"].get<std::string>() : "";
          if (type.empty()) type = (n == "x" || n == "y" || n == "z") ? "space" : n == "t" ? "time" : n == "c" ? "channel" : "";
          s.axis_types.push_back(type);
          s.axis_units.push_back(a.contains("unit") && a["unit"].is_string() ? a["unit"].get<std::string>() : "");
        } else {
          throw Error(attrs_path, "OME axis is not a name or {\"name\": ...}");
        }
      }
    }
    for (const auto& d : datasets) {
      if (!d.is_object() || !d.contains("path") || !d["path"].is_string())
        throw Error(attrs_path, "OME dataset has no path");
      Level l;
      l.name = d["path"].get<std::string>();
      if (l.name.empty() || l.name.find("..") != std::string::npos || l.name[0] == '/')
        throw Error(attrs_path, "OME dataset path '" + l.name + "' is not a path inside the store");
      l.path = zarr_join(path, l.name);
      l.meta = read_array_meta(l.path);
      const std::size_t n = l.meta.shape.size();
      if (s.axis_names.empty()) default_axes(s, n, l.meta.dimension_names);
      if (s.axis_names.size() != n)
        throw Error(l.meta.meta_path, "the array has " + std::to_string(n) + " dimensions, the OME axes " +
                                          std::to_string(s.axis_names.size()));
      l.scale.assign(n, 1.0);
      l.translation.assign(n, 0.0);
      apply_transforms(attrs_path, d.contains("coordinateTransformations") ? d["coordinateTransformations"] : json(),
                       l.scale, l.translation);
      apply_transforms(attrs_path, m.contains("coordinateTransformations") ? m["coordinateTransformations"] : json(),
                       l.scale, l.translation);
      s.levels.push_back(std::move(l));
    }
  } catch (const json::exception& e) {
    throw Error(attrs_path, std::string("malformed OME metadata: ") + e.what());
  }
  map_spatial_axes(s, attrs_path);
  return s;
}

}  // namespace isocurv::volume::zarr_detail
