#pragma once
// The rendering options shared by isocurv render, run and view.
#include <CLI/CLI.hpp>

#include "viz/render_options.h"

namespace isocurv::app {

/// Adds --color, --ao, --dirs, --size WxH (into opts.width/height) to `cmd`.
void add_render_options(CLI::App& cmd, viz::RenderOptions& opts);

}  // namespace isocurv::app
