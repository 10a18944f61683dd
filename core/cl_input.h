#pragma once
// Host arrays as kernel inputs without a copy where the device works in host memory.
// Tested in tests/curvature/batagelo_test.cpp (through its users).
#include <algorithm>
#include <cstddef>
#include <vector>

#include "core/cl_device.h"

namespace isocurv {

/// Whether `device` runs in host memory (a CPU device such as PoCL's), so that a buffer made
/// with CL_MEM_USE_HOST_PTR is the host array itself. The one switch between reading host
/// arrays in place and copying them.
inline bool works_in_host_memory(const Device& device) { return device.info().type == "CPU"; }

/// A read-only device buffer over a host array, for the kernels of one call. On devices that work
/// in host memory it wraps the array's own memory (nothing is copied: the kernels read it in
/// place); elsewhere it copies the array into a device buffer that it keeps between calls, grown
/// by half again when too small. Either way the array must stay alive and unchanged until the
/// commands that read the buffer have completed. Not thread-safe: one caller at a time, like the
/// device's queue.
class InputBuffer {
 public:
  /// The buffer holding `v` for kernels enqueued on `device`'s queue after this call: wrapped, or
  /// an enqueued (non-blocking) copy. An empty `v` gives a small unused buffer (a valid kernel
  /// argument).
  template <class T, class A>
  cl::Buffer& bind(Device& device, const std::vector<T, A>& v) {
    const std::size_t bytes = v.size() * sizeof(T);
    if (bytes > 0 && works_in_host_memory(device)) {
      // A fresh wrapper each time: an implementation may cache the array when the buffer is made.
      wrapped_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes,
                            const_cast<T*>(v.data()));
      return *(last_ = &wrapped_);
    }
    wrapped_ = cl::Buffer();
    if (bytes > copy_bytes_ || copy_() == nullptr) {
      copy_bytes_ = std::max<std::size_t>({bytes, copy_bytes_ + copy_bytes_ / 2, 16});
      copy_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY, copy_bytes_);
    }
    if (bytes > 0) device.queue().enqueueWriteBuffer(copy_, CL_FALSE, 0, bytes, v.data());
    return *(last_ = &copy_);
  }

  /// The buffer of the last bind(), for a call that reuses what the previous one bound (its host
  /// array still alive and unchanged). Null before the first bind.
  cl::Buffer* bound() { return last_; }

  /// Drops the wrapper of the host array; call once the array may go away (a later bound() is
  /// then null unless the last bind copied).
  void release() {
    if (last_ == &wrapped_) last_ = nullptr;
    wrapped_ = cl::Buffer();
  }

 private:
  cl::Buffer wrapped_, copy_;
  cl::Buffer* last_ = nullptr;
  std::size_t copy_bytes_ = 0;
};

}  // namespace isocurv
