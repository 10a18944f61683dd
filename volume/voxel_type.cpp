#include "volume/voxel_type.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstring>

namespace isocurv::volume {
namespace {

template <class T>
void decode(const std::uint8_t* bytes, std::size_t count, bool swap, float* out) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1 << 16), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint8_t b[sizeof(T)];
      std::memcpy(b, bytes + i * sizeof(T), sizeof(T));
      if (swap)
        for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
      T v;
      std::memcpy(&v, b, sizeof(T));
      out[i] = float(v);
    }
  });
}

bool host_is_big_endian() {
  const std::uint16_t one = 1;
  std::uint8_t first;
  std::memcpy(&first, &one, 1);
  return first == 0;
}

}  // namespace

std::optional<VoxelType> parse_voxel_type(const std::string& name) {
  if (name == "uint8") return VoxelType::UInt8;
  if (name == "int8") return VoxelType::Int8;
  if (name == "uint16") return VoxelType::UInt16;
  if (name == "int16") return VoxelType::Int16;
  if (name == "uint32") return VoxelType::UInt32;
  if (name == "int32") return VoxelType::Int32;
  if (name == "float" || name == "float32") return VoxelType::Float32;
  if (name == "double" || name == "float64") return VoxelType::Float64;
  return std::nullopt;
}

std::string voxel_type_name(VoxelType t) {
  switch (t) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::Int8: return "int8";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Int16: return "int16";
    case VoxelType::UInt32: return "uint32";
    case VoxelType::Int32: return "int32";
    case VoxelType::Float32: return "float";
    case VoxelType::Float64: return "double";
  }
  return "unknown";
}

std::size_t voxel_size(VoxelType t) {
  switch (t) {
    case VoxelType::UInt8:
    case VoxelType::Int8: return 1;
    case VoxelType::UInt16:
    case VoxelType::Int16: return 2;
    case VoxelType::UInt32:
    case VoxelType::Int32:
    case VoxelType::Float32: return 4;
    case VoxelType::Float64: return 8;
  }
  return 1;
}

void decode_voxels(const std::uint8_t* bytes, std::size_t count, VoxelType t, bool big_endian, float* out) {
  const bool swap = big_endian != host_is_big_endian();
  switch (t) {
    case VoxelType::UInt8: decode<std::uint8_t>(bytes, count, false, out); break;
    case VoxelType::Int8: decode<std::int8_t>(bytes, count, false, out); break;
    case VoxelType::UInt16: decode<std::uint16_t>(bytes, count, swap, out); break;
    case VoxelType::Int16: decode<std::int16_t>(bytes, count, swap, out); break;
    case VoxelType::UInt32: decode<std::uint32_t>(bytes, count, swap, out); break;
    case VoxelType::Int32: decode<std::int32_t>(bytes, count, swap, out); break;
    case VoxelType::Float32: decode<float>(bytes, count, swap, out); break;
    case VoxelType::Float64: decode<double>(bytes, count, swap, out); break;
  }
}

}  // namespace isocurv::volume
