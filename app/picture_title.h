#pragma once
// The one title scheme of every picture (render, run, view).
#include <optional>
#include <string>

#include "app/pipeline.h"
#include "curvature/estimator.h"

namespace isocurv::app {

/// "NAME  |  QUANTITY  |  iso V  |  ESTIMATOR": the input's file name (no folders), the colour
/// quantity's description (viz::quantity_description), the isovalue (volumes only, %g) and the
/// curvature estimator ("Rusinkiewicz", or "curvature from the file" for a mesh file whose arrays
/// were shown as they are; empty, or a label map's Label shown: left out).
std::string picture_title(const std::string& input, const std::string& quantity,
                          std::optional<float> isovalue, const std::string& estimator);

/// The estimator as titles name it, from what an estimate used: "rusinkiewicz", "volume, scale
/// 1.5" (a given scale, %g), "volume, scale 1.25-3.53 per vertex" (the default's per-vertex
/// scales, 5th to 95th percentile); empty when nothing was estimated.
std::string estimator_title(const curvature::EstimatorReport& report);

/// The same from the options, before any estimate (the explorer's titles, checks): --estimator
/// (or the default) and --scale as given.
std::string estimator_title(const CommonOptions& o);

/// `estimator` followed by ", AO METHOD" when --ao-method chose another AO than the default griffin, so
/// a picture coloured or shaded by AO says which (e.g. "rusinkiewicz, AO raycast").
std::string with_ao(const std::string& estimator, const CommonOptions& o);

}  // namespace isocurv::app
