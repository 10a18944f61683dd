#pragma once
// Setting a kernel's arguments and launching it over n work items with a fixed work-group size.
// PoCL compiles one work-group function per distinct local size (about 100 ms each): leaving the
// local size to the runtime would recompile for every new problem size, so every launch names it.
// Tested in tests/features/test_sampled.cpp (through its users).
#include <cstddef>

#include "core/cl_device.h"

namespace isocurv {

/// Sets k's arguments 0, 1, ... to args in order.
template <class... Args>
void set_args(cl::Kernel& k, const Args&... args) {
  cl_uint i = 0;
  (k.setArg(i++, args), ...);
}

/// Enqueues k over `items` work items (rounded up to a multiple of `group`, so kernels must ignore
/// ids >= items) in work groups of `group`. Nothing is enqueued when items is 0.
inline void launch(cl::CommandQueue& q, cl::Kernel& k, std::size_t items, std::size_t group) {
  if (items > 0) q.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(round_up(items, group)), cl::NDRange(group));
}

}  // namespace isocurv
