// isocurv lines VOLUME|MESH -o lines.vtp|lines.svg: feature lines (contours,
// suggestive contours, ridges, valleys) from the curvature, as polylines or as
// a drawing of the visible ones (several inputs or isovalues: a batch, app/batch.h).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "core/atomic_file.h"
#include "app/batch.h"
#include "app/commands.h"
#include "app/label_surfaces.h"
#include "app/line_options_cli.h"
#include "app/pipeline.h"
#include "app/series.h"
#include "app/render_options_cli.h"
#include "core/error.h"
#include "lines/line_files.h"
#include "lines/visibility.h"

namespace isocurv::app {
namespace {

/// The lines of one surface, ready to write.
struct LinesResult {
  nlohmann::json report;  ///< the --json report without input, output and timings
  lines::Polylines poly;
  Camera cam;
  std::size_t kept = 0, all = 0;  ///< segments written, and before the visibility test
};

/// The camera, lines, (for .svg) their visible part and the polylines of `s` (as loaded), the
/// curvature estimated first when it lacks arrays; the report counts them.
LinesResult compute_lines(Surface &s, const std::string &in, const CommonOptions &o,
                          const lines::Options &lo, const ViewSpec &view,
                          const AnatomicalCli &anatomical, int width, int height, bool svg,
                          StageTimer &timer) {
  LinesResult l;
  if (!o.labelled())  // a label map's surfaces come with each label's own curvature
    ensure_curvature(s, in, o, timer);
  l.cam = picture_camera(
      s.mesh, resolve_view(view, anatomical, surface_context(s).world_space, in), width, height);
  lines::Segments segs = extract_lines(s.mesh, *s.field, l.cam, lo, o, timer);
  l.all = segs.size();
  if (svg) {
    timer.start("visibility");
    segs = lines::select_segments(
        segs, lines::VisibilityTester(s.mesh).visible_segments(segs, l.cam));
  }
  l.kept = segs.size();
  timer.start("join");
  l.poly = lines::join_segments(segs);
  nlohmann::json counts = nlohmann::json::object(),
                 lengths = nlohmann::json::object();
  for (int t = 0; t < lines::kLineTypeCount; ++t) {
    const auto type = lines::LineType(t);
    if (!lo.lines.has(type))
      continue;
    std::size_t n = 0;
    for (const lines::Segment &g : segs)
      n += g.type == type;
    counts[lines::to_string(type)] = n;
    lengths[lines::to_string(type)] = l.poly.length(type);
  }
  nlohmann::json &r = l.report;
  r = surface_report(s);
  r["lines"] = lo.lines.to_string();
  r["segments"] = counts;
  r["segments_before_visibility"] = l.all;
  r["polylines"] = l.poly.line_count();
  r["length"] = lengths;
  r["device"] = device_name(o);
  return l;
}

/// Writes the lines: the drawing (.svg) or the polylines (.vtp).
void write_lines(const std::string &path, const LinesResult &l, bool svg, int width,
                 int height) {
  if (svg)
    lines::write_svg(path, l.poly, l.cam, width, height);
  else
    lines::write_vtp(path, l.poly);
}

/// The parsed --lines options; a bad list is a usage error.
lines::Options parsed_line_options(const LineCli &lc) {
  try {
    return line_options(lc);
  } catch (const Error &e) {
    throw CLI::ValidationError("--lines", e.what());
  }
}

} // namespace

void register_lines(CLI::App &app) {
  auto *cmd = app.add_subcommand(
      "lines", "Feature lines of a volume's isosurface or a mesh: polylines "
               "(.vtp) or a line drawing (.svg)");
  cmd->footer("Example: isocurv lines ../shared/datasets/vg_bunny/bunny-128.vol --lines contours,suggestive "
              "--view +x -o bunny.svg\n"
              "The camera is the one isocurv render would use with the same "
              "camera options and --size, so\n"
              "render --lines draws the same lines. .vtp: every line, with "
              "cell arrays LineType (0 contour,\n"
              "1 suggestive, 2 ridge, 3 valley) and Strength; .svg: only the "
              "visible lines (ray cast\n"
              "against the surface). A mesh without curvature arrays gets them "
              "estimated first.");
  static CommonOptions o;
  static LineCli lc;
  static ViewSpec view;
  static AnatomicalCli anatomical;
  static int width = 1024, height = 768;
  static std::string out;
  static BatchCli b;
  static SeriesCli series;
  add_batch_options(*cmd, b, "VOLUME_OR_MESH", "Volume or mesh file", {"vtp", "svg"});
  cmd->add_option("-o,--output", out,
                  "Lines file to write: .vtp (polylines) or .svg (drawing), or the folder of a "
                  "batch")
      ->required();
  add_common_options(*cmd, o, false);
  add_curvature_options(*cmd, o, true);
  add_label_options(*cmd, o, false);
  add_line_options(*cmd, lc, "contours,suggestive");
  add_camera_options(*cmd, view, &anatomical);
  cmd->add_option_function<std::string>(
         "--size",
         [](const std::string &s) {
           int w = 0, h = 0;
           char x = 0;
           if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 ||
               (x != 'x' && x != 'X') || w < 16 || h < 16 || w > 8192 ||
               h > 8192)
             throw CLI::ValidationError(
                 "--size",
                 "expected WIDTHxHEIGHT, each 16..8192, e.g. 1024x768");
           width = w;
           height = h;
         },
         "Drawing size WIDTHxHEIGHT (default 1024x768; also fits the camera)")
      ->group("Camera");
  add_series_options(*cmd, series);
  // One input -> `out`; prints its summary unless `quiet_summary` (a series frame). Returns the
  // --json report.
  static auto one = [](const std::string& in, const std::string& out, CommonOptions& o,
                       bool quiet_summary) -> nlohmann::json {
    const std::string ext = std::filesystem::path(out).extension().string();
    const bool svg = ext == ".svg" || ext == ".SVG";
    if (!svg && ext != ".vtp" && ext != ".VTP")
      throw Error(
          out,
          "isocurv lines writes .vtp (polylines) or .svg (a drawing), not '" +
              ext + "'");
    require_writable_file(out);  // before any work
    const lines::Options lo = parsed_line_options(lc);
    require_lines_supported(lo.lines, o);
    StageTimer timer;
    Surface s = o.labelled() ? load_label_surfaces(in, o, timer, true) : load_surface(in, o, timer);
    const LinesResult l =
        compute_lines(s, in, o, lo, view, anatomical, width, height, svg, timer);
    timer.start("write");
    write_lines(out, l, svg, width, height);
    timer.stop();
    nlohmann::json r = l.report;
    r["input"] = in;
    r["output"] = out;
    r["timings_ms"] = timer.json();
    if (quiet_summary) {
    } else if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << ": " << l.poly.line_count()
                << " polylines from " << l.kept << " segments";
      if (svg)
        std::cout << " (" << l.all - l.kept << " hidden segments left out)";
      std::cout << "\n";
    }
    return r;
  };
  // A batch entry: the same computation and file (--format vtp|svg); stats.json holds the --json
  // report.
  static const BatchStep step{
      "lines", true, [](Surface &s, const std::string &in, StageTimer &timer) {
        const bool svg = b.format == "svg";
        auto l = std::make_shared<LinesResult>(compute_lines(
            s, in, o, parsed_line_options(lc), view, anatomical, width, height, svg, timer));
        BatchStep::Output out;
        out.report = l->report;
        out.write = [l, svg](const std::string &path) {
          write_lines(path, *l, svg, width, height);
        };
        out.summary_keys = {"lines", "segments", "segments_before_visibility", "polylines",
                            "length"};
        return out;
      }};
  cmd->callback([] {
    if (series.enabled) {
      require_series_cli(b, o);
      run_series(b.inputs, series, {"lines", out}, o,
                 [](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                   return one(f.path, path, fo, true);
                 });
      return;
    }
    // A batch checks first what every entry would fail on: --lines and the estimator.
    if (run_as_batch(b, o, step, out,
                     [] { require_lines_supported(parsed_line_options(lc).lines, o); }))
      return;
    one(b.inputs.front(), out, o, false);
  });
}

} // namespace isocurv::app
