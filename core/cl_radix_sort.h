#pragma once
// Stable LSD radix sort of (key, value) pairs on the device (vertex fusion, vertex adjacency).
// Tested in tests/core/scan_sort_test.cpp.
#include "core/cl_device.h"

namespace isocurv {

/// Enqueues on the device's queue a stable sort of n (key, value) uint pairs by the low `key_bits`
/// bits of key (1..32; higher bits must be zero), in place in `keys` and `values`: as few passes
/// as digits of at most 11 bits allow, the bits shared evenly between them. Does not wait: later
/// commands on the queue (and blocking reads) see the sorted pairs.
void enqueue_radix_sort_pairs(Device& dev, cl::Buffer& keys, cl::Buffer& values, std::uint32_t n, int key_bits);

}  // namespace isocurv
