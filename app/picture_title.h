#pragma once
// The one title scheme of every picture (render, run, view).
#include <optional>
#include <string>

namespace isocurv::app {

/// "NAME  |  QUANTITY  |  iso V  |  ESTIMATOR": the input's file name (no folders), the colour
/// quantity's description (viz::quantity_description), the isovalue (volumes only, %g) and the
/// curvature estimator ("Rusinkiewicz", or "curvature from the file" for a mesh file whose arrays
/// were shown as they are; empty: left out).
std::string picture_title(const std::string& input, const std::string& quantity,
                          std::optional<float> isovalue, const std::string& estimator);

/// The estimator named in titles for the curvature the commands compute.
inline const char* kEstimatorName = "Rusinkiewicz";

}  // namespace isocurv::app
