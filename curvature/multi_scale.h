#pragma once
// Curvature at several scales in one field: the volume estimator run once per scale, each run's
// scalar arrays kept under a suffix "_s<name>" (e.g. "H_s2" for --scale 2), as the command line
// spells the scale, so users can see structure by scale (ParaView, `render --color H_s2`).
// Tested through --scale S1,S2: tests/app/test_volume_options.cpp.
#include <string>
#include <vector>

#include "curvature/curvature_field.h"

namespace isocurv::curvature {

/// The arrays kept per scale, in this order: k1 k2 H K ShapeIndex Curvedness, and Unreliable (as
/// 0/1 floats) when the run flagged any vertex. Directions, normals, dcurv and AO are not
/// repeated per scale.
const std::vector<std::string>& per_scale_arrays();

/// The array name for `array` at scale `scale_name`: "<array>_s<scale_name>".
std::string scale_array_name(const std::string& array, const std::string& scale_name);

/// Appends `at_scale`'s per_scale_arrays() to `out.extra`, suffixed for `scale_name`.
/// @throw Error when `at_scale` does not have one value per vertex of `out`, or `out` already has
///        an array of one of those names (the same scale given twice).
void append_scale_arrays(const CurvatureField& at_scale, const std::string& scale_name,
                         CurvatureField& out);

}  // namespace isocurv::curvature
