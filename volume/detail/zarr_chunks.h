#pragma once
// Reading a region of a Zarr array (v2 or v3, sharded or not) into a dense float buffer: only the
// chunks that overlap the region are read, missing chunks are the fill value, and chunks are
// decoded in parallel, each into its own part of the output (the result does not depend on the
// thread count). Every problem is an isocurv::Error naming the chunk's file.
// Tested in tests/volume/test_zarr.cpp.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "volume/detail/zarr_metadata.h"

namespace isocurv::volume::zarr_detail {

/// The region read: array indices [lo, hi) per dimension, and where each lands in the output
/// (offset = sum over dimensions of (index - lo) * out_stride).
struct Region {
  std::vector<long long> lo, hi;
  std::vector<std::int64_t> out_stride;
};

/// Fills `out` (the region's voxel count) with the array's fill value, then decodes every chunk
/// file overlapping the region into it. Returns the number of chunk files read.
std::size_t read_region(const ArrayMeta& meta, const Region& region, float* out, std::size_t out_count);

/// The relative path of chunk `index` ("0.1.2", "0/1/2", "c/0/1/2").
std::string chunk_key(const ArrayMeta& meta, const std::vector<long long>& index);

/// CRC-32C (Castagnoli), as Zarr's crc32c codec stores it.
std::uint32_t crc32c(const std::uint8_t* data, std::size_t size);

}  // namespace isocurv::volume::zarr_detail
