#pragma once
// Headless rendering of a curvature surface to a PNG.
// Tested in tests/viz/test_render.cpp.
#include <string>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include <functional>

#include "core/camera.h"
#include "lines/polylines.h"
#include "viz/picture_layout.h"
#include "viz/render_options.h"

namespace isocurv::viz {

/// Lines to draw over the surface, made from the camera the picture is seen with (contours and
/// suggestive contours depend on it; it is only known once the surface is laid out and framed).
using LinesForCamera = std::function<lines::Polylines(const Camera&)>;

/// Renders `mesh` coloured by `options.color` through `options.cmap` (color_map.h; range by
/// color_range), shaded as `options.shading` says, with the legend, optional direction glyphs
/// and the title laid out beside the surface (picture_layout.h), framed by `options.view` or
/// `options.camera`, offscreen at options.width x height, and writes the PNG atomically. Starts
/// a private Xvfb when there is no X display (ensure_display). Throws Error for an empty
/// mesh, a bad size, an unknown or missing quantity, or a failed write. Returns where the
/// surface, title and legend were put. `lines`, when given, is called with the camera once the
/// surface is framed and its lines are drawn over the surface, hidden parts removed by the depth
/// test (viz/line_overlay.h).
PictureLayout render_png(const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field,
                         const RenderOptions& options = {}, const LinesForCamera& lines = {});

}  // namespace isocurv::viz
