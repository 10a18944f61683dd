#pragma once
// Exclusive prefix sum on the device (the mesher's offsets, the radix sort).
#include "core/cl_device.h"

namespace isocurv {

/// Writes the exclusive prefix sum of in[0..n) to out[0..n) (out may equal in) and returns the
/// total. Integer arithmetic: deterministic. Blocks until done. Throws on OpenCL failure.
std::uint32_t exclusive_scan(Device& dev, const cl::Buffer& in, const cl::Buffer& out, std::uint32_t n);

}  // namespace isocurv
