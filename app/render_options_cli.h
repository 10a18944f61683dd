#pragma once
// The rendering options shared by isocurv render, run and view.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "viz/render_options.h"

namespace isocurv::app {

/// What the rendering options fill in: the viz options, and the files named on the command line.
struct RenderCli {
  viz::RenderOptions opts;
  std::string camera_file;  ///< --camera FILE: a camera saved by the explorer ('k')
  std::string dirs_out;     ///< --dirs-out FILE.vtp: the direction glyphs as line cells
  std::string title;        ///< --title TEXT: replaces the title scheme (picture_title)
};

/// Adds --color, --cmap, --range, --percentile, --shading, --ao, --dirs, --dirs-count,
/// --dirs-length, --size WxH, --title, --unit, the camera options and --camera; `files` adds
/// --dirs-out (render and run).
void add_render_options(CLI::App& cmd, RenderCli& r, bool files = true);

/// Adds --view iso|+x|-x|+y|-y|+z|-z, --azimuth DEG, --elevation DEG, --zoom F and --ortho.
void add_camera_options(CLI::App& cmd, ViewSpec& view);

/// The options to render with: r.opts with --camera loaded and the title set (r.title, else
/// picture_title(input, quantity, isovalue, estimator)). @throw Error for a bad camera file.
viz::RenderOptions render_options_for(const RenderCli& r, const std::string& input,
                                      std::optional<float> isovalue, const std::string& estimator);

}  // namespace isocurv::app
