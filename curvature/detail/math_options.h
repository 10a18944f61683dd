#pragma once
// The build options curvature/curvature_math.cl needs (its tolerances and Griffin's AO
// polynomial), from their C++ definitions: every program that includes curvature_math.cl starts
// its options with these.
#include <cstdio>
#include <string>

#include "curvature/derived.h"
#include "curvature/tolerances.h"

namespace isocurv::curvature::detail {

inline std::string math_build_options() {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "-DPIVOT_TOLERANCE=%.9g -DOPPOSITE_NORMALS=%.9g -DAO_C0=%.9g -DAO_C1=%.9g "
                "-DAO_C2=%.9g -DAO_SMIN=%.9g",
                kPivotTolerance, kOppositeNormals, kAoC0, kAoC1, kAoC2, kAoSMin);
  return buf;
}

}  // namespace isocurv::curvature::detail
