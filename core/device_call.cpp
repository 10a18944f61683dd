// The device-error boundary (see device_call.h).
#include "core/device_call.h"

namespace isocurv {

void drain_queue(Device& device) noexcept {
  try {
    device.queue().finish();
  } catch (...) {
  }
}

Error device_error(Device& device, const std::string& stage, const cl::Error& e) {
  return Error(stage + ": OpenCL call " + (e.what() ? e.what() : "?") + " failed on " +
               device.info().name + ": " + cl_error_name(e.err()));
}

}  // namespace isocurv
