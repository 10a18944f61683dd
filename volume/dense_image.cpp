#include "volume/dense_image.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "volume/file_bytes.h"
#include "volume/from_dense.h"
#include "volume/from_dense_u8.h"

namespace isocurv::volume {

std::uint64_t checked_voxel_count(const std::string& path, const std::array<long long, 3>& dims) {
  const std::string text = std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" + std::to_string(dims[2]);
  for (long long d : dims)
    if (d <= 0 || d > 0x7fffffffLL) throw Error(path, "invalid dimensions " + text);
  const long double count = (long double)dims[0] * dims[1] * dims[2];
  if (count > (long double)(1ULL << 40)) throw Error(path, "dimensions " + text + " are implausibly large");
  return std::uint64_t(dims[0]) * std::uint64_t(dims[1]) * std::uint64_t(dims[2]);
}

std::string bytes_text(long double bytes) {
  if (bytes < 1e9L) return std::to_string(std::uint64_t(bytes)) + " bytes";
  char text[32];
  std::snprintf(text, sizeof text, "%.3Lg bytes", bytes);
  return text;
}

std::uint64_t checked_payload(const std::string& path, const std::array<long long, 3>& dims, VoxelType type,
                              const std::string& data_path, std::uint64_t available, Payload payload,
                              const std::string& source) {
  const std::string text = std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]);
  for (long long d : dims)
    if (d <= 0 || d > 0x7fffffffLL) throw Error(path, "invalid dimensions " + text);
  const long double count = (long double)dims[0] * dims[1] * dims[2];
  const long double needed = count * voxel_size(type);
  const std::string claim = source + " claims " + text + " " + voxel_type_name(type) + " voxels (" + bytes_text(needed) + ")";
  const std::string holds = data_path == path ? "the file holds" : "data file '" + data_path + "' holds";
  switch (payload) {
    case Payload::Raw:
      if (needed > (long double)available)
        throw Error(path, claim + " but " + holds + " " + bytes_text(available));
      break;
    case Payload::Compressed:
      if (needed > (long double)max_inflated(available))
        throw Error(path, claim + " but " + holds + " " + bytes_text(available) + " compressed, which inflate to " +
                              "at most " + bytes_text((long double)max_inflated(available)));
      break;
    case Payload::Ascii:
      if (count > (long double)available / 2 + 1)
        throw Error(path, claim + " but " + holds + " " + bytes_text(available) + " of text, at most " +
                              std::to_string(available / 2 + 1) + " numbers");
      break;
  }
  return checked_voxel_count(path, dims);
}

void decode_into(DenseImage& image, Bytes&& bytes, std::uint64_t offset, std::uint64_t count, VoxelType type,
                 bool big_endian) {
  image.voxel_type = voxel_type_name(type);
  if (type == VoxelType::UInt8 && offset == 0 && bytes.size() == count) {
    image.u8 = std::move(bytes);
    image.values = {};
    return;
  }
  image.values = LargeBuffer<float>(count);
  decode_voxels(bytes.data() + offset, count, type, big_endian, image.values.data());
  bytes = {};
}

void ensure_float(DenseImage& image) {
  if (image.u8.empty()) return;
  image.values = LargeBuffer<float>(image.u8.size());
  decode_voxels(image.u8.data(), image.u8.size(), VoxelType::UInt8, false, image.values.data());
  image.u8 = {};
}

openvdb::math::Transform::Ptr make_transform(const std::array<double, 3>& spacing,
                                             const std::array<double, 3>& origin,
                                             const std::array<std::array<double, 3>, 3>& axes) {
  bool identity = true;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) identity &= axes[i][j] == (i == j ? 1.0 : 0.0);
  if (identity) {
    auto map = std::make_shared<openvdb::math::ScaleTranslateMap>(
        openvdb::Vec3d(spacing[0], spacing[1], spacing[2]), openvdb::Vec3d(origin[0], origin[1], origin[2]));
    return std::make_shared<openvdb::math::Transform>(map);
  }
  // OpenVDB matrices act on row vectors: world = index * M, so row i is index axis i in world space.
  openvdb::Mat4d m = openvdb::Mat4d::identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = spacing[std::size_t(i)] * axes[std::size_t(i)][std::size_t(j)];
  for (int j = 0; j < 3; ++j) m(3, j) = origin[std::size_t(j)];
  return openvdb::math::Transform::createLinearTransform(m);
}

Volume finish_dense(DenseImage&& image, const std::string& path, const std::string& format,
                    const LoadOptions& options) {
  // --spacing / --origin replace the header's values before anything uses them.
  const auto file_spacing = image.spacing, file_origin = image.origin;
  if (options.spacing) image.spacing = *options.spacing;
  if (options.origin) image.origin = *options.origin;
  auto& a = image.axes;
  for (std::size_t i = 0; i < 3; ++i) {
    const double s = image.spacing[i];
    if (!std::isfinite(s) || s == 0) {
      char value[32];
      std::snprintf(value, sizeof value, "%g", s);
      throw Error(path, std::string("invalid voxel spacing ") + value + " (axis " + char('x' + i) +
                            "): it must be finite and non-zero");
    }
    // A negative spacing is a flip: world = origin + index * spacing * axis in every format, so
    // the axis turns around and the spacing is its length (the flip itself is resolved below).
    if (s < 0) {
      image.spacing[i] = -s;
      for (double& c : a[i]) c = -c;
    }
    if (!std::isfinite(image.origin[i])) throw Error(path, "invalid origin: it must be three finite numbers");
  }
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  if (!std::isfinite(det) || std::fabs(det) < 1e-6) throw Error(path, "degenerate direction matrix");
  // World positions are doubles: each voxel step must stay far above their resolution (a z origin
  // of 4.8e24 with spacing 2 put every slice at the same world position).
  double largest = 0;
  for (std::size_t j = 0; j < 3; ++j) {
    double coord = std::fabs(image.origin[j]);
    for (std::size_t i = 0; i < 3; ++i)
      coord += double((i == 2 && image.full_z ? image.full_z : image.dims[i]) - 1) * image.spacing[i] * std::fabs(a[i][j]);
    largest = std::max(largest, coord);
  }
  if (!std::isfinite(largest)) throw Error(path, "the volume's world box is not finite");
  for (std::size_t i = 0; i < 3; ++i)
    if (image.spacing[i] < largest * 0x1p-40) {
      char text[96];
      std::snprintf(text, sizeof text, "voxel spacing %g is too small for world coordinates up to %g",
                    image.spacing[i], largest);
      throw Error(path, std::string(text) + ": world positions cannot resolve the voxels");
    }
  if (det < 0) {
    // Reverse X: voxel x becomes nx-1-x; the first voxel now sits where the last one was.
    const int nx = image.dims[0];
    const std::size_t rows = std::size_t(image.dims[1]) * std::size_t(image.dims[2]);
    auto reverse_rows = [&](auto* v) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t row = r.begin(); row != r.end(); ++row) std::reverse(v + row * nx, v + (row + 1) * nx);
      });
    };
    if (!image.u8.empty())
      reverse_rows(image.u8.data());
    else
      reverse_rows(image.values.data());
    for (int j = 0; j < 3; ++j) {
      image.origin[std::size_t(j)] += double(nx - 1) * image.spacing[0] * a[0][std::size_t(j)];
      a[0][std::size_t(j)] = -a[0][std::size_t(j)];
    }
  }
  DenseSource source;
  source.path = path;
  source.format = format;
  source.voxel_type = image.voxel_type;
  source.grid_name = image.array_name;
  source.inside = options.inside.value_or(Inside::Above);
  DensePart part;
  part.first_z = image.first_z;
  part.full_z = image.full_z;
  part.outside = options.outside;
  auto xform = make_transform(image.spacing, image.origin, image.axes);
  Volume v = !image.u8.empty() ? from_dense_u8(image.u8.data(), image.dims, xform, source, part)
                               : from_dense(image.values.data(), image.dims, xform, source, part);
  if (options.spacing)
    v.file_spacing = openvdb::Vec3d(file_spacing[0], file_spacing[1], file_spacing[2]);
  if (options.origin)
    v.file_origin = openvdb::Vec3d(file_origin[0], file_origin[1], file_origin[2]);
  return v;
}

void read_uncompressed(DenseImage& image, const std::string& data_path, std::uint64_t offset, VoxelType type,
                       bool big_endian, const LoadOptions& options) {
  const std::uint64_t slice = std::uint64_t(image.dims[0]) * std::uint64_t(image.dims[1]);
  const int depth = image.dims[2];
  int first = 0, last = depth - 1;
  if (options.z_slab) {
    first = std::clamp((*options.z_slab)[0], 0, depth - 1) & ~7;
    last = std::clamp((*options.z_slab)[1], first, depth - 1);
    last = std::min(depth - 1, last | 7);
  }
  const std::uint64_t count = slice * std::uint64_t(last - first + 1);
  const std::uint64_t bytes = count * voxel_size(type);
  decode_into(image, read_bytes(data_path, offset + slice * std::uint64_t(first) * voxel_size(type), bytes), 0,
              count, type, big_endian);
  if (options.z_slab) {
    image.first_z = first;
    image.full_z = depth;
    image.dims[2] = last - first + 1;
  }
}

}  // namespace isocurv::volume
