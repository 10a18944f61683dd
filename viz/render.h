#pragma once
// Headless rendering of a curvature surface to a PNG.
#include <string>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "viz/render_options.h"

namespace isocurv::viz {

/// Renders `mesh` coloured by `options.color` (blue negative, green zero, red positive; range
/// clamped by percentile, see color_range), with a scalar bar, optional AO shading, direction
/// glyphs and title, framed from a three-quarter view, offscreen at options.width x height, and
/// writes the PNG atomically. Starts a private Xvfb when there is no X display
/// (ensure_display). Throws Error for an empty mesh, a bad size, an unknown or missing quantity,
/// or a failed write.
void render_png(const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field,
                const RenderOptions& options = {});

}  // namespace isocurv::viz
