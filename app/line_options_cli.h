#pragma once
// What isocurv lines, render --lines, run --lines and view share: the line
// options, the camera a picture of the mesh would have, and the extraction on
// the chosen device.
#include <CLI/CLI.hpp>

#include <string>

#include "app/pipeline.h"
#include "core/camera.h"
#include "lines/options.h"
#include "lines/polylines.h"
#include "lines/segments.h"

namespace isocurv::app {

/// The command line's line options (before parsing --lines).
struct LineCli {
  std::string
      list; ///< --lines: comma list (lines::parse_line_selection); empty: none
  lines::Options options; ///< --suggestive-threshold, --suggestive-angle,
                          ///< --line-smoothing, --ridge-threshold
};

/// Adds --lines (with `default_list` shown as its default; empty: no lines
/// unless given),
/// --suggestive-threshold, --suggestive-angle, --line-smoothing and
/// --ridge-threshold to `cmd`.
void add_line_options(CLI::App &cmd, LineCli &cli,
                      const std::string &default_list);

/// cli.options with the parsed --lines selection. @throw Error for a bad list.
lines::Options line_options(const LineCli &cli);

/// Refuses, before any work, a selection the --estimator cannot feed: suggestive
/// contours, ridges and valleys need principal directions and the curvature
/// derivative, which prantl2, prantl3 and meyer do not give (contours work with
/// every estimator). @throw Error, one line naming the estimator and the ones
/// that would do.
void require_lines_supported(const lines::LineSelection &lines, const CommonOptions &o);

/// The camera render and the explorer use for `mesh` in a width x height
/// picture: fit_camera over the mesh's bounds with `view`.
Camera picture_camera(const Mesh &mesh, const ViewSpec &view, int width,
                      int height);

/// The feature-line segments (stage "lines") on the device --device chose (the
/// C++ reference for --device reference). @throw Error (a field without dcurv,
/// ...).
lines::Segments extract_lines(const Mesh &mesh,
                              const curvature::CurvatureField &field,
                              const Camera &camera,
                              const lines::Options &options,
                              const CommonOptions &o, StageTimer &timer);

/// A curvature field for the lines: the mesh file's own (when it has every
/// array the lines need) or a fresh estimate (stage "curvature"; a note on
/// stderr names the estimator unless
/// --quiet). Readies a mesh file's mesh first (prepare_mesh_for_curvature).
void ensure_curvature(Surface &s, const std::string &path,
                      const CommonOptions &o, StageTimer &timer);

} // namespace isocurv::app
