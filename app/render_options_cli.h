#pragma once
// The rendering options shared by isocurv render, run and view.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "app/pipeline.h"
#include "curvature/curvature_field.h"
#include "viz/render_options.h"

namespace isocurv::app {

/// The camera options that need the input's anatomical frame, resolved by resolve_view.
struct AnatomicalCli {
  std::string view;          ///< --view anterior|posterior|left|right|superior|inferior
  std::string up;            ///< --view-up superior|inferior|anterior|posterior|left|right
  bool view_given = false;   ///< --view was given (else an anatomical input gets its own iso)
};

/// What the rendering options fill in: the viz options, and the files named on the command line.
struct RenderCli {
  viz::RenderOptions opts;
  std::string camera_file;      ///< --camera FILE: a camera saved by the explorer ('k')
  std::string dirs_out;         ///< --dirs-out FILE.vtp: the direction glyphs as line cells
  std::string title;            ///< --title TEXT: replaces the title scheme (picture_title)
  AnatomicalCli anatomical;     ///< --view and --view-up by anatomical names
  /// --range shared|each: several pictures (sweep, batch, series) share one colour range and
  /// camera (app/shared_pictures.h), or each has its own. A MIN,MAX range is in opts.range.
  std::string range_mode = "shared";
};

/// Parses a MIN,MAX (one value) or MIN MAX (two) colour range into `out`; false unless both are
/// finite numbers with MIN < MAX.
bool parse_min_max(const std::vector<std::string>& values, viz::ColorRange& out);

/// Adds --color, --cmap, --range, --percentile, --shading, --ao, --dirs, --dirs-count,
/// --dirs-length, --size WxH, --title, --unit, the camera options and --camera; `files` adds
/// --dirs-out (render and run).
void add_render_options(CLI::App& cmd, RenderCli& r, bool files = true);

/// Adds --view iso|+x|-x|+y|-y|+z|-z, --view-up +x..-z|X,Y,Z, --azimuth DEG, --elevation DEG
/// (-180..180), --roll DEG, --zoom F and --ortho; with `anatomical`, --view and --view-up also
/// take anterior, posterior, left, right, superior, inferior (stored there, resolved by
/// resolve_view).
void add_camera_options(CLI::App& cmd, ViewSpec& view, AnatomicalCli* anatomical = nullptr);

/// `view` with the anatomical --view/--view-up resolved in `world_space` (Volume::world_space, or
/// a mesh file's), and, when --view was not given and the input has an anatomical frame, the
/// anatomical iso view (from the front, above, superior up). @throw Error naming `input` for an
/// anatomical name on an input without an anatomical frame.
ViewSpec resolve_view(const ViewSpec& view, const AnatomicalCli& anatomical,
                      const std::string& world_space, const std::string& input);

/// The anatomical frame of a volume's world coordinates, from its Volume::world_space ("RAS" for
/// NIfTI, "LPS" for MetaImage, NRRD's `space`); none for an empty or other value.
std::optional<AnatomicalFrame> anatomical_frame(const std::string& world_space);

/// The options to render with: r.opts with --camera loaded, an anatomical --view resolved for
/// context.world_space (the volume's, or a mesh file's field data), the length unit from
/// context.length_unit unless --unit gave one, the colour array resolved in `field` when given
/// (viz::resolve_quantity: its spelling there), and the title set (r.title, else
/// picture_title(input, quantity, context.isovalue, estimator)). @throw Error for a bad camera
/// file, an anatomical view of an input without an anatomical frame, or a colour array `field`
/// does not carry (the message lists those it does).
viz::RenderOptions render_options_for(const RenderCli& r, const std::string& input,
                                      const SurfaceContext& context, const std::string& estimator,
                                      const curvature::CurvatureField* field = nullptr);

}  // namespace isocurv::app
