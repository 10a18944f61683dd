#pragma once
// The isovalue a volume is extracted at, checked against its values once for the command line
// (app/pipeline.cpp, "FILE: ...") and the Python module (extract(), "iso: ...").
// Tested in tests/curvature/request_test.cpp.
#include <optional>

#include "core/error.h"
#include "volume/volume.h"

namespace isocurv::volume {

/// A rejected isovalue: what() is the problem alone ("isovalue 300 is outside the value range
/// [0, 246.34]"), for the caller to prefix with the file or the argument it came from.
class IsovalueError : public Error {
 public:
  using Error::Error;
};

/// The isovalue to extract `v` at: `requested`, or v.stats.suggested_isovalue when it is empty.
/// @throw IsovalueError when it is not finite, when a requested one lies outside [min, max], or
/// when it equals the end of the range where no voxel can be inside (the tie rule: a voxel equal
/// to the isovalue is outside, so the maximum for Inside::Above, the minimum for Below, leaves no
/// surface)
float checked_isovalue(const Volume& v, std::optional<float> requested);

}  // namespace isocurv::volume
