#pragma once
// The values a picture's automatic colour range is taken from, so that a picture, a sweep's shared
// range and the statistics all count the same vertices.
// Tested through the pictures' colour ranges: tests/viz/test_render.cpp.
#include <string>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"

namespace isocurv::viz {

/// The values of quantity `quantity` (viz::quantity_values' name) over the vertices the
/// statistics count (curvature::counted_vertices: measured, finite, not a spike the mesh cannot
/// resolve), less the open-boundary vertices (a surface cut by the volume's box: their one-sided
/// curvature would set the scale) and those flagged Unreliable. When that leaves nothing, every
/// value. Feed them to color_range. @throw Error for a quantity the field does not carry.
std::vector<float> range_values(const Mesh& mesh, const curvature::CurvatureField& field,
                                const std::string& quantity);

}  // namespace isocurv::viz
