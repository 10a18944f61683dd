#pragma once
// The rendering options shared by isocurv render, run and view.
#include <CLI/CLI.hpp>

#include "viz/render_options.h"

namespace isocurv::app {

/// Adds --color, --ao, --dirs, --size WxH (into opts.width/height) and the camera options to `cmd`.
void add_render_options(CLI::App& cmd, viz::RenderOptions& opts);

/// Adds --view iso|+x|-x|+y|-y|+z|-z, --azimuth DEG, --elevation DEG, --zoom F and --ortho.
void add_camera_options(CLI::App& cmd, ViewSpec& view);

}  // namespace isocurv::app
