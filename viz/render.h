#pragma once
// Headless rendering of a curvature surface to a PNG.
#include <string>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "lines/polylines.h"
#include "viz/render_options.h"

namespace isocurv::viz {

/// Renders `mesh` coloured by `options.color` (blue negative, green zero, red positive; range
/// clamped by percentile, see color_range), with a scalar bar, optional AO shading, direction
/// glyphs and title, framed from a three-quarter view, offscreen at options.width x height, and
/// writes the PNG atomically. Starts a private Xvfb when there is no X display
/// (ensure_display). Throws Error for an empty mesh, a bad size, an unknown or missing quantity,
/// or a failed write. `lines`, when given, are drawn over the surface (viz/line_overlay.h); for
/// view-dependent lines, extract them with the camera fit_camera gives for the mesh's bounds,
/// options.view and width/height (the camera used here).
void render_png(const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field,
                const RenderOptions& options = {}, const lines::Polylines* lines = nullptr);

}  // namespace isocurv::viz
