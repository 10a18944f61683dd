#include "screen/detail/kernels.h"

#include <cstdio>
#include <string>

#include "curvature/tolerances.h"
#include "volume/dense_field.h"

namespace isocurv::kernels {
extern const char* const screen_kernels_cl;
extern const char* const dense_field_cl;
}  // namespace isocurv::kernels

namespace isocurv::screen::detail {

cl::Program& screen_program(Device& device) {
  char options[128];
  std::snprintf(options, sizeof options, "-DPIVOT_TOLERANCE=%.9g -DBRICK=%d.0f",
                curvature::kPivotTolerance, volume::kFieldBrick);
  static const std::string source =
      std::string(kernels::dense_field_cl) + "\n" + kernels::screen_kernels_cl;
  return device.program("screen", source.c_str(), options);
}

}  // namespace isocurv::screen::detail
