#pragma once
// Zarr v2 and v3 array metadata and OME-NGFF multiscales (0.4 in .zattrs, 0.5 in zarr.json's
// "ome" attributes), parsed into one form the chunk reader (zarr_chunks.h) takes. Every problem
// is an isocurv::Error naming the metadata file.
// Tested in tests/volume/test_zarr.cpp.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/voxel_type.h"

namespace isocurv::volume::zarr_detail {

/// One codec of a chunk's pipeline, in Zarr v3's encoding order (v2's order, compressor and
/// dtype byte order are translated into the same form).
struct Codec {
  enum class Kind { Transpose, Bytes, Sharding, Gzip, Zlib, Zstd, Blosc, Crc32c };
  Kind kind = Kind::Bytes;
  std::string name;                    ///< as the metadata names it, for messages and `info`
  std::vector<int> order;              ///< transpose: the permutation
  bool big_endian = false;             ///< bytes: the byte order of multi-byte elements
  // sharding_indexed
  std::vector<long long> inner_chunks; ///< the inner chunks' shape
  std::vector<Codec> inner;            ///< the inner chunks' codecs
  std::vector<Codec> index_codecs;     ///< the shard index's codecs
  bool index_at_end = true;
};

/// What one array's metadata says.
struct ArrayMeta {
  std::string dir;                     ///< the array's folder
  std::string meta_path;               ///< .zarray or zarr.json, for messages
  int zarr_format = 2;
  std::vector<long long> shape, chunks;  ///< array order (C order: the last index fastest)
  VoxelType type = VoxelType::UInt8;
  double fill = 0;                     ///< fill value as a double (NaN allowed)
  std::vector<Codec> codecs;
  bool c_prefix = false;               ///< v3 default key encoding: "c/0/0/0"
  std::string separator = ".";         ///< between the chunk indices of a key
  std::vector<std::string> dimension_names;  ///< v3 dimension_names (empty strings when unnamed)
};

/// Reads the array in `dir` (.zarray or zarr.json with node_type "array"); checks the shape
/// (positive, its product without overflow), the chunk shape (a decoded chunk at most 2 GiB),
/// the data type and every codec.
ArrayMeta read_array_meta(const std::string& dir);

/// "blosc(zstd) <- bytes(little)" style text of a pipeline, outermost first.
std::string codecs_text(const std::vector<Codec>& codecs);

/// One resolution level of a store.
struct Level {
  std::string path;                    ///< the array's folder
  std::string name;                    ///< its dataset path in the multiscales ("0"), or "."
  ArrayMeta meta;
  /// Per array dimension: the combined scale and translation (the dataset's transformations,
  /// then the multiscale's).
  std::vector<double> scale, translation;
};

/// A store: one array, or an OME-NGFF multiscale group.
struct Store {
  std::string path;
  int zarr_format = 2;
  std::string ome_version;             ///< "" when the store is a bare array
  std::vector<std::string> axis_names; ///< per array dimension ("t", "c", "z", "y", "x")
  std::vector<std::string> axis_types; ///< "space", "time", "channel" or other
  std::vector<std::string> axis_units; ///< as written ("micrometer"), "" when absent
  std::string length_unit;             ///< the spatial axes' common unit, short ("um"), or ""
  std::array<int, 3> spatial{0, 0, 0}; ///< array dimensions of volume x, y, z
  std::vector<Level> levels;           ///< finest first, as the multiscales list them
};

/// True when `path` is a folder holding .zarray, .zattrs, .zgroup or zarr.json, or is named
/// *.zarr (an error then says what is missing).
bool looks_like_zarr(const std::string& path);

/// Reads a store's metadata: every level's array metadata, axes and transformations.
Store read_store(const std::string& path);

/// The short form of an OME-NGFF unit ("micrometer" -> "um"); "" for an unknown one.
std::string short_unit(const std::string& unit);

}  // namespace isocurv::volume::zarr_detail
