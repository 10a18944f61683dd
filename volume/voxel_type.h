#pragma once
// On-disk scalar voxel types and their conversion to float.
// Tested in tests/volume/test_reader_honesty.cpp (through its users).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace isocurv::volume {

enum class VoxelType { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };

/// Parses the names Volume::voxel_type uses ("uint8", "int8", "uint16", "int16", "uint32",
/// "int32", "float", "double"), plus "float32"/"float64"; nullopt for anything else.
std::optional<VoxelType> parse_voxel_type(const std::string& name);

/// Canonical name ("uint8", ..., "float", "double").
std::string voxel_type_name(VoxelType t);

/// Bytes per voxel.
std::size_t voxel_size(VoxelType t);

/// Converts `count` voxels of type `t` (byte order: big-endian when `big_endian`) from `bytes`
/// to floats in `out`, in parallel. `bytes` must hold count * voxel_size(t) bytes.
void decode_voxels(const std::uint8_t* bytes, std::size_t count, VoxelType t, bool big_endian, float* out);

}  // namespace isocurv::volume
