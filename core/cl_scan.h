#pragma once
// Exclusive prefix sum on the device (the mesher's offsets, the radix sort).
// Tested in tests/core/scan_sort_test.cpp.
#include "core/cl_device.h"

namespace isocurv {

/// Enqueues the exclusive prefix sum of in[0..n) into out[0..n) (out may equal in) and, when
/// `total` is given, the sum of all n into (*total)[index] (a uint buffer). Returns at once: later
/// work on the device's in-order queue sees the results. Integer arithmetic: deterministic.
/// Throws on OpenCL failure.
void enqueue_exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n,
                            const cl::Buffer* total = nullptr, std::uint32_t index = 0);

/// The same, blocking until done; returns the total.
std::uint32_t exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n);

}  // namespace isocurv
