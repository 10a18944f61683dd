#pragma once
// The screen stage's OpenCL program (screen_kernels.cl), built once per device.
#include "core/cl_device.h"

namespace isocurv::screen::detail {

/// The program with its build options (the pivot tolerance, the brick size).
cl::Program& screen_program(Device& device);

}  // namespace isocurv::screen::detail
