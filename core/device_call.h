#pragma once
// The one boundary between OpenCL failures and isocurv's errors (after VTK-m's TryExecute): every
// stage runs its device calls inside device_call, which drains the queue before anything unwinds
// and words the failure one way. Tested in tests/core/test_device_call.cpp.
#include <exception>
#include <string>
#include <utility>

#include "core/cl_device.h"
#include "core/error.h"

namespace isocurv {

/// Waits until everything queued on `device` has finished. Queued copies may still write into host
/// memory, and kernels read buffers, that an unwinding stack is about to free: drain first. A
/// failure while waiting is ignored (the caller is already handling one). Thread safety: that of
/// the queue (the stages serialise their calls per device).
void drain_queue(Device& device) noexcept;

/// The error an OpenCL failure in `stage` becomes, one line:
/// "<stage>: OpenCL call <call> failed on <device name>: <CL_ERROR_NAME>". `stage` names the work
/// ("curvature", "features: building the kernels"), after the file's name where there is one
/// ("lobster.nrrd: marching cubes").
Error device_error(Device& device, const std::string& stage, const cl::Error& e);

/// Drains `device`'s queue when an exception unwinds it: declared after the host arrays that queued
/// copies read or write, it runs before they are freed (destructors run in reverse order).
class DrainOnUnwind {
 public:
  explicit DrainOnUnwind(Device& device) : device_(device) {}
  DrainOnUnwind(const DrainOnUnwind&) = delete;
  DrainOnUnwind& operator=(const DrainOnUnwind&) = delete;
  ~DrainOnUnwind() {
    if (std::uncaught_exceptions() > pending_) drain_queue(device_);
  }

 private:
  Device& device_;
  int pending_ = std::uncaught_exceptions();
};

/// Runs f() and returns what it returns. When f throws, the device's queue is drained first; a
/// cl::Error then becomes device_error(device, stage, e) (an isocurv::Error), any other
/// exception goes on unchanged. f's own locals are gone before that drain: host memory that queued
/// copies read or write lives outside f, or behind a DrainOnUnwind declared after it.
template <class F>
decltype(auto) device_call(Device& device, const std::string& stage, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (const cl::Error& e) {
    drain_queue(device);
    throw device_error(device, stage, e);
  } catch (...) {
    drain_queue(device);
    throw;
  }
}

}  // namespace isocurv
