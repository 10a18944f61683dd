#pragma once
// The curvature colour map (DESIGN.md: blue negative, green zero, red positive, symmetric around
// zero), its percentile-clamped range, and per-vertex colours with optional AO shading.
#include <string>
#include <vector>

#include <vtkSmartPointer.h>

class vtkColorTransferFunction;
class vtkUnsignedCharArray;

namespace isocurv::viz {

/// The value range mapped onto the colour map, from blue (lo) through green to red (hi).
struct ColorRange {
  double lo = -1, hi = 1;
};

/// The range for `values` of quantity `name`, ignoring non-finite values:
///  - signed quantities (H, K, k1, k2): symmetric [-r, r], r = the (100 - clamp_percentile)th
///    percentile of |value|, so a few outliers do not wash the map out (green stays zero);
///  - ShapeIndex: its natural range [-1, 1];
///  - Curvedness, AO (never negative): [the clamp_percentile-th, the (100 - clamp_percentile)th
///    percentile], over the whole map.
/// A degenerate range (all values equal) is widened so that it is never empty.
ColorRange color_range(const std::vector<float>& values, const std::string& name, double clamp_percentile);

/// The blue-green-red map over `range` (values outside are clamped to the end colours), for
/// the scalar bar; vertex_colors uses the same map.
vtkSmartPointer<vtkColorTransferFunction> make_color_map(const ColorRange& range);

/// RGB colours (unsigned char, 3 components, named "Colors") for `values` through `map` over
/// `range`; when `ao` is non-null each colour is multiplied by the vertex's AO (clamped to
/// [0, 1]). Non-finite values are grey.
vtkSmartPointer<vtkUnsignedCharArray> vertex_colors(const std::vector<float>& values, const ColorRange& range,
                                                    vtkColorTransferFunction* map,
                                                    const std::vector<float>* ao = nullptr);

}  // namespace isocurv::viz
