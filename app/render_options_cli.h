#pragma once
// The rendering options shared by isocurv render, run and view.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "curvature/curvature_field.h"
#include "viz/render_options.h"

namespace isocurv::app {

/// What the rendering options fill in: the viz options, and the files named on the command line.
struct RenderCli {
  viz::RenderOptions opts;
  std::string camera_file;      ///< --camera FILE: a camera saved by the explorer ('k')
  std::string dirs_out;         ///< --dirs-out FILE.vtp: the direction glyphs as line cells
  std::string title;            ///< --title TEXT: replaces the title scheme (picture_title)
  std::string anatomical_view;  ///< --view anterior|posterior|left|right|superior|inferior
};

/// Adds --color, --cmap, --range, --percentile, --shading, --ao, --dirs, --dirs-count,
/// --dirs-length, --size WxH, --title, --unit, the camera options and --camera; `files` adds
/// --dirs-out (render and run).
void add_render_options(CLI::App& cmd, RenderCli& r, bool files = true);

/// Adds --view iso|+x|-x|+y|-y|+z|-z, --azimuth DEG, --elevation DEG, --zoom F and --ortho;
/// with `anatomical`, --view also takes anterior, posterior, left, right, superior, inferior
/// (stored there, resolved by render_options_for).
void add_camera_options(CLI::App& cmd, ViewSpec& view, std::string* anatomical = nullptr);

/// The anatomical frame of a volume's world coordinates, from its Volume::world_space ("RAS" for
/// NIfTI, "LPS" for MetaImage, NRRD's `space`); none for an empty or other value.
std::optional<AnatomicalFrame> anatomical_frame(const std::string& world_space);

/// The options to render with: r.opts with --camera loaded, an anatomical --view resolved for
/// `world_space` (the input volume's Volume::world_space; empty for a mesh file), the colour
/// array resolved in `field` when given (viz::resolve_quantity: its spelling there), and the
/// title set (r.title, else picture_title(input, quantity, isovalue, estimator)). @throw Error
/// for a bad camera file, an anatomical view of an input without an anatomical frame, or a
/// colour array `field` does not carry (the message lists those it does).
viz::RenderOptions render_options_for(const RenderCli& r, const std::string& input,
                                      std::optional<float> isovalue, const std::string& estimator,
                                      const std::string& world_space = "",
                                      const curvature::CurvatureField* field = nullptr);

}  // namespace isocurv::app
