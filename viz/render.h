#pragma once
// Headless rendering of a curvature surface to a PNG.
#include <string>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "viz/picture_layout.h"
#include "viz/render_options.h"

namespace isocurv::viz {

/// Renders `mesh` coloured by `options.color` through `options.cmap` (color_map.h; range by
/// color_range), shaded as `options.shading` says, with the legend, optional direction glyphs
/// and the title laid out beside the surface (picture_layout.h), framed by `options.view` or
/// `options.camera`, offscreen at options.width x height, and writes the PNG atomically. Starts
/// a private Xvfb when there is no X display (ensure_display). Throws Error for an empty
/// mesh, a bad size, an unknown or missing quantity, or a failed write. Returns where the
/// surface, title and legend were put.
PictureLayout render_png(const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field,
                const RenderOptions& options = {});

}  // namespace isocurv::viz
