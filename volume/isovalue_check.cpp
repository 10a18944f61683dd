#include "volume/isovalue_check.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace isocurv::volume {

namespace {

std::string isovalue_number(double x) {  // %g, as the messages print numbers
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

}  // namespace

float checked_isovalue(const Volume& v, std::optional<float> requested) {
  const float value = requested ? *requested : static_cast<float>(v.stats.suggested_isovalue);
  if (!std::isfinite(value)) throw IsovalueError("isovalue must be a finite number");
  const std::string range =
      "[" + isovalue_number(v.stats.min) + ", " + isovalue_number(v.stats.max) + "]";
  if (requested && (value < v.stats.min || value > v.stats.max))
    throw IsovalueError("isovalue " + isovalue_number(value) + " is outside the value range " +
                        range);
  // The tie rule: a voxel equal to the isovalue is outside, so at the top of the range (bottom
  // when the object is below the isovalue) no voxel is inside and there is no surface.
  const bool above = v.inside == Inside::Above;
  if (value == static_cast<float>(above ? v.stats.max : v.stats.min))
    throw IsovalueError("isovalue " + isovalue_number(value) + " equals the " +
                        (above ? "maximum" : "minimum") +
                        " value, so there is no surface: a voxel equal to the isovalue counts as "
                        "outside, and none is " + (above ? "above" : "below") +
                        " it (the range is " + range + ")");
  return value;
}

}  // namespace isocurv::volume
