#pragma once
// Identity of a cube edge (the key vertex fusion compares) and its hash. Mirrored in mc/*.cl.
#include <cstdint>

namespace isocurv::mc {

/// Key of the voxel-grid edge starting at index (x, y, z) (relative to the extraction's key
/// origin, each 0 .. 2^20-1) along axis 0/1/2: 20 bits a coordinate, then 2 bits of axis.
inline std::uint64_t edge_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, std::uint32_t axis) {
  return (std::uint64_t(x) << 42) | (std::uint64_t(y) << 22) | (std::uint64_t(z) << 2) | axis;
}

/// 32-bit hash of an edge key (murmur3's 64-bit finaliser), keeping the low `bits` bits.
inline std::uint32_t edge_hash(std::uint64_t key, int bits) {
  key ^= key >> 33;
  key *= 0xff51afd7ed558ccdULL;
  key ^= key >> 33;
  key *= 0xc4ceb9fe1a85ec53ULL;
  key ^= key >> 33;
  const std::uint32_t mask = bits >= 32 ? 0xffffffffu : ((1u << bits) - 1u);
  return static_cast<std::uint32_t>(key) & mask;
}

/// Largest coordinate span (voxels) an extraction can key.
constexpr std::int64_t kMaxKeySpan = (1 << 20) - 2;

}  // namespace isocurv::mc
