#pragma once
// A small Zarr store writer for the tests: the metadata as JSON text written by the test, the
// chunks cut from an array held in memory (C order), encoded by a function the test gives
// (compressed with zlib, zstd or blosc as a real writer would), in C or F order, either byte
// order, and sharded (Zarr v3 sharding_indexed) with the index at either end.
#include <blosc.h>
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tests/volume/test_files.h"
#include "volume/detail/zarr_chunks.h"

namespace zarrtest {

using Encode = std::function<std::vector<std::uint8_t>(const std::vector<std::uint8_t>&)>;
using Index = std::vector<long long>;

inline std::vector<std::uint8_t> zstd_compress(const std::vector<std::uint8_t>& in) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(in.size()));
  out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
  return out;
}

inline std::vector<std::uint8_t> blosc_compress(const std::vector<std::uint8_t>& in, int typesize) {
  std::vector<std::uint8_t> out(in.size() + BLOSC_MAX_OVERHEAD);
  const int n = blosc_compress_ctx(5, BLOSC_SHUFFLE, std::size_t(typesize), in.size(), in.data(), out.data(),
                                   out.size(), "zstd", 0, 1);
  out.resize(std::size_t(n > 0 ? n : 0));
  return out;
}

/// A value as `type` ("u1" "i1" "u2" "i2" "u4" "i4" "f4" "f8") bytes.
inline void put_value(std::vector<std::uint8_t>& out, double v, const std::string& type, bool big) {
  std::uint8_t b[8];
  std::size_t n = 0;
  auto put = [&](auto x) {
    n = sizeof(x);
    std::memcpy(b, &x, n);
  };
  if (type == "u1") put(std::uint8_t(int(v)));  // wraps, as numpy's astype does
  else if (type == "i1") put(std::int8_t(int(v)));
  else if (type == "u2") put(std::uint16_t(v));
  else if (type == "i2") put(std::int16_t(v));
  else if (type == "u4") put(std::uint32_t(v));
  else if (type == "i4") put(std::int32_t(v));
  else if (type == "f4") put(float(v));
  else put(double(v));
  if (big) std::reverse(b, b + n);
  out.insert(out.end(), b, b + n);
}

struct Array {
  Index shape;
  std::vector<double> values;  // C order
  std::string type = "u2";
  bool big = false;
  double pad = 0;              // beyond the array's edge in edge chunks

  /// The elements of the box [origin, origin + cshape) as bytes, C order (or F order).
  std::vector<std::uint8_t> chunk(const Index& origin, const Index& cshape, bool forder = false) const {
    const std::size_t n = shape.size();
    std::size_t count = 1;
    for (auto s : cshape) count *= std::size_t(s);
    std::vector<std::uint8_t> out;
    for (std::size_t k = 0; k < count; ++k) {
      // k enumerates the chunk in storage order: C (last fastest) or F (first fastest).
      Index at(n);
      std::size_t r = k;
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t d = forder ? i : n - 1 - i;
        at[d] = (long long)(r % std::size_t(cshape[d]));
        r /= std::size_t(cshape[d]);
      }
      bool inside = true;
      std::size_t flat = 0;
      for (std::size_t d = 0; d < n; ++d) {
        const long long a = origin[d] + at[d];
        inside = inside && a < shape[d];
        flat = flat * std::size_t(shape[d]) + std::size_t(std::min(a, shape[d] - 1));
      }
      put_value(out, inside ? values[flat] : pad, type, big);
    }
    return out;
  }
};

/// Every chunk index of a grid of `cshape` chunks over `shape`.
inline std::vector<Index> chunk_grid(const Index& shape, const Index& cshape) {
  std::vector<Index> out{Index(shape.size(), 0)};
  for (std::size_t d = 0; d < shape.size(); ++d) {
    std::vector<Index> next;
    const long long n = (shape[d] + cshape[d] - 1) / cshape[d];
    for (const Index& i : out)
      for (long long k = 0; k < n; ++k) {
        Index j = i;
        j[d] = k;
        next.push_back(j);
      }
    out = next;
  }
  return out;
}

inline std::string join_key(const Index& i, const std::string& sep, bool c_prefix) {
  std::string k = c_prefix ? "c" : "";
  for (auto v : i) k += (k.empty() ? "" : sep) + std::to_string(v);
  return k;
}

/// Writes every chunk of `a` (those in `skip` left out) under `dir`, each encoded by `encode`.
inline void write_chunks(const std::string& dir, const Array& a, const Index& cshape, const Encode& encode,
                         const std::string& sep, bool c_prefix, bool forder = false, const std::set<Index>& skip = {}) {
  for (const Index& i : chunk_grid(a.shape, cshape)) {
    if (skip.count(i)) continue;
    Index origin(i.size());
    for (std::size_t d = 0; d < i.size(); ++d) origin[d] = i[d] * cshape[d];
    const std::string path = dir + "/" + join_key(i, sep, c_prefix);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    voltest::write_file(path, encode(a.chunk(origin, cshape, forder)));
  }
}

inline void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int k = 0; k < 8; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
}

/// Writes the shards of `a` (shape `sshape`, inner chunks `ishape`, each encoded by `encode`; the
/// inner chunks in `skip_inner`, by their index in the whole array's inner grid, left out), the
/// index little-endian with a crc32c, at the end or the start.
inline void write_shards(const std::string& dir, const Array& a, const Index& sshape, const Index& ishape,
                         const Encode& encode, bool index_at_end, const std::set<Index>& skip_inner = {}) {
  const std::size_t n = a.shape.size();
  for (const Index& s : chunk_grid(a.shape, sshape)) {
    Index counts(n);
    for (std::size_t d = 0; d < n; ++d) counts[d] = sshape[d] / ishape[d];
    std::vector<std::vector<std::uint8_t>> parts;
    std::vector<bool> present;
    for (const Index& k : chunk_grid(sshape, ishape)) {
      Index origin(n), global(n);
      for (std::size_t d = 0; d < n; ++d) {
        global[d] = s[d] * counts[d] + k[d];
        origin[d] = global[d] * ishape[d];
      }
      bool inside = true;
      for (std::size_t d = 0; d < n; ++d) inside = inside && origin[d] < a.shape[d];
      present.push_back(inside && !skip_inner.count(global));
      parts.push_back(present.back() ? encode(a.chunk(origin, ishape)) : std::vector<std::uint8_t>{});
    }
    const std::uint64_t index_bytes = parts.size() * 16 + 4;
    std::vector<std::uint8_t> body, index;
    std::uint64_t offset = index_at_end ? 0 : index_bytes;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      if (!present[k]) {
        put_u64(index, ~std::uint64_t(0));
        put_u64(index, ~std::uint64_t(0));
        continue;
      }
      put_u64(index, offset);
      put_u64(index, parts[k].size());
      body.insert(body.end(), parts[k].begin(), parts[k].end());
      offset += parts[k].size();
    }
    const std::uint32_t crc = isocurv::volume::zarr_detail::crc32c(index.data(), index.size());
    for (int k = 0; k < 4; ++k) index.push_back(std::uint8_t(crc >> (8 * k)));
    std::vector<std::uint8_t> file = index_at_end ? body : index;
    const auto& rest = index_at_end ? index : body;
    file.insert(file.end(), rest.begin(), rest.end());
    const std::string path = dir + "/" + join_key(s, "/", true);
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    voltest::write_file(path, file);
  }
}

inline std::string json_list(const Index& v) {
  std::string t = "[";
  for (std::size_t i = 0; i < v.size(); ++i) t += (i ? ", " : "") + std::to_string(v[i]);
  return t + "]";
}

/// A v2 .zarray.
inline std::string zarray(const Array& a, const Index& chunks, const std::string& compressor, const std::string& fill = "0",
                          const std::string& order = "C", const std::string& sep = ".") {
  const std::string dtype = std::string(a.type == "u1" || a.type == "i1" ? "|" : a.big ? ">" : "<") + a.type;
  return "{\"zarr_format\": 2, \"shape\": " + json_list(a.shape) + ", \"chunks\": " + json_list(chunks) +
         ", \"dtype\": \"" + dtype + "\", \"compressor\": " + compressor + ", \"fill_value\": " + fill +
         ", \"order\": \"" + order + "\", \"filters\": null, \"dimension_separator\": \"" + sep + "\"}";
}

/// A v3 array zarr.json.
inline std::string zarr_json_array(const Array& a, const Index& chunks, const std::string& codecs,
                                   const std::string& fill = "0", const std::string& keys = "{\"name\": \"default\"}") {
  static const std::map<std::string, std::string> names{{"u1", "uint8"}, {"i1", "int8"},   {"u2", "uint16"},
                                                         {"i2", "int16"}, {"u4", "uint32"}, {"i4", "int32"},
                                                         {"f4", "float32"}, {"f8", "float64"}};
  return "{\"zarr_format\": 3, \"node_type\": \"array\", \"shape\": " + json_list(a.shape) +
         ", \"data_type\": \"" + names.at(a.type) +
         "\", \"chunk_grid\": {\"name\": \"regular\", \"configuration\": {\"chunk_shape\": " + json_list(chunks) +
         "}}, \"chunk_key_encoding\": " + keys + ", \"fill_value\": " + fill + ", \"codecs\": " + codecs +
         ", \"attributes\": {}}";
}

}  // namespace zarrtest
