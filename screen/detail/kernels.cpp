#include "screen/detail/kernels.h"

#include <cstdio>

#include "curvature/tolerances.h"
#include "screen/cast_volume.h"

namespace isocurv::kernels {
extern const char* const screen_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::screen::detail {

cl::Program& screen_program(Device& device) {
  char options[128];
  std::snprintf(options, sizeof options, "-DPIVOT_TOLERANCE=%.9g -DBRICK=%d.0f",
                curvature::kPivotTolerance, kCastBrick);
  return device.program("screen", kernels::screen_kernels_cl, options);
}

}  // namespace isocurv::screen::detail
