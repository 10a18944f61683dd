#pragma once
// The common last step of every dense loader: decoded voxels plus geometry -> Volume.
// Tested in tests/volume/test_loaders.cpp (through its users).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/large_buffer.h"
#include "volume/load.h"
#include "volume/voxel_type.h"

namespace isocurv::volume {

/// A decoded dense image: voxels X fastest, and index -> world geometry
/// world = origin + sum_i index_i * spacing_i * axes[i].
struct DenseImage {
  std::array<int, 3> dims{0, 0, 0};
  LargeBuffer<float> values;       ///< X fastest (empty when u8 holds the voxels)
  LargeBuffer<std::uint8_t> u8;    ///< uint8 voxels kept as they are, X fastest (else empty)
  std::array<double, 3> spacing{1, 1, 1};
  std::array<double, 3> origin{0, 0, 0};
  std::array<std::array<double, 3>, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  ///< unit axis directions
  std::string voxel_type;
  std::string array_name;
  /// A slab (LoadOptions::z_slab): the voxels are index-z slices [first_z, first_z + dims[2]) of
  /// an image `full_z` slices deep; 0: the whole image.
  int first_z = 0, full_z = 0;
};

/// Checks a header's dimensions (positive, at most 2^31-1 per axis and 2^40 voxels in all) and
/// returns the voxel count; throws Error(path, ...) otherwise.
std::uint64_t checked_voxel_count(const std::string& path, const std::array<long long, 3>& dims);

/// How a payload is stored, which bounds the voxels a number of bytes can hold.
enum class Payload {
  Raw,         ///< voxel_size(type) bytes per voxel
  Compressed,  ///< deflate (zlib, gzip): at most max_inflated(bytes) out (file_bytes.h)
  Ascii,       ///< a number and a separator per voxel: at least two bytes (bar the last)
};

/// checked_voxel_count, and before anything is allocated, that `available` bytes of `data_path`
/// (the payload, stored as `payload`) can hold the header's voxels of `type`; throws, e.g.
/// "header claims 100000 x 100000 x 100000 uint8 voxels (1e+15 bytes) but the file holds 352
/// bytes" (`source` names what claims: "header", or "layout" for raw files). Returns the voxel count.
std::uint64_t checked_payload(const std::string& path, const std::array<long long, 3>& dims, VoxelType type,
                              const std::string& data_path, std::uint64_t available, Payload payload,
                              const std::string& source = "header");

/// A byte count for messages: exact below 10^9, else 3 significant digits ("1e+15 bytes").
std::string bytes_text(long double bytes);

/// Takes `count` voxels of `type` starting at byte `offset` of `bytes` (sets image.voxel_type):
/// uint8 voxels filling the whole buffer are adopted as image.u8 without a copy, anything else
/// is decoded into image.values.
void decode_into(DenseImage& image, Bytes&& bytes, std::uint64_t offset, std::uint64_t count, VoxelType type,
                 bool big_endian);

/// The voxels of an image stored uncompressed at byte `offset` of `data_path` (image.dims set to
/// the whole image's), decoded into `image`: every voxel, or with options.z_slab only those
/// slices, rounded out to whole 8-voxel blocks and clamped (image.dims[2], first_z and full_z
/// then describe the slab). The caller has checked that the file holds the whole payload.
void read_uncompressed(DenseImage& image, const std::string& data_path, std::uint64_t offset, VoxelType type,
                       bool big_endian, const LoadOptions& options);

/// Converts image.u8 (if used) to image.values, for loaders that rescale voxels.
void ensure_float(DenseImage& image);

/// Builds the Volume: the index -> world transform (axes are used as given when they form a
/// right-handed frame; a left-handed frame is made right-handed by reversing the voxel order along
/// X and moving the origin to the old last slice, which describes the same world-space image), the
/// inside side (options.inside, else Above), and from_dense.
Volume finish_dense(DenseImage&& image, const std::string& path, const std::string& format,
                    const LoadOptions& options);

/// The index -> world transform for spacing, origin and unit axis directions (a scale-translate
/// map when the axes are the identity, else an affine map).
openvdb::math::Transform::Ptr make_transform(const std::array<double, 3>& spacing,
                                             const std::array<double, 3>& origin,
                                             const std::array<std::array<double, 3>, 3>& axes);

}  // namespace isocurv::volume
