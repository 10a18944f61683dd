// isocurv lines VOLUME|MESH -o lines.vtp|lines.svg: feature lines (contours,
// suggestive contours, ridges, valleys) from the curvature, as polylines or as
// a drawing of the visible ones.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "core/atomic_file.h"
#include "app/commands.h"
#include "app/line_options_cli.h"
#include "app/pipeline.h"
#include "app/series.h"
#include "app/render_options_cli.h"
#include "core/error.h"
#include "lines/line_files.h"
#include "lines/visibility.h"

namespace isocurv::app {

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
  static std::vector<std::string> ins;
  static SeriesCli series;
  cmd->add_option("VOLUME_OR_MESH", ins,
                  "Volume or mesh file (several, or a quoted glob, with --time-series)")
      ->required();
  cmd->add_option("-o,--output", out,
                  "Lines file to write: .vtp (polylines) or .svg (drawing)")
      ->required();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o, true);
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
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error &e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    require_lines_supported(lo.lines, o);
    StageTimer timer;
    Surface s = load_surface(in, o, timer);
    ensure_curvature(s, in, o, timer);
    const Camera cam = picture_camera(
        s.mesh, resolve_view(view, anatomical, surface_context(s).world_space, in), width, height);
    lines::Segments segs = extract_lines(s.mesh, *s.field, cam, lo, o, timer);
    const std::size_t all = segs.size();
    if (svg) {
      timer.start("visibility");
      segs = lines::select_segments(
          segs, lines::VisibilityTester(s.mesh).visible_segments(segs, cam));
    }
    timer.start("join");
    const lines::Polylines poly = lines::join_segments(segs);
    timer.start("write");
    if (svg)
      lines::write_svg(out, poly, cam, width, height);
    else
      lines::write_vtp(out, poly);
    timer.stop();
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
      lengths[lines::to_string(type)] = poly.length(type);
    }
    nlohmann::json r = surface_report(s);
    r["input"] = in;
    r["output"] = out;
    r["lines"] = lo.lines.to_string();
    r["segments"] = counts;
    r["segments_before_visibility"] = all;
    r["polylines"] = poly.line_count();
    r["length"] = lengths;
    r["device"] = device_name(o);
    r["timings_ms"] = timer.json();
    if (quiet_summary) {
    } else if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << ": " << poly.line_count()
                << " polylines from " << segs.size() << " segments";
      if (svg)
        std::cout << " (" << all - segs.size() << " hidden segments left out)";
      std::cout << "\n";
    }
    return r;
  };
  cmd->callback([] {
    if (series.enabled) {
      run_series(ins, series, {"lines", out}, o,
                 [](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                   return one(f.path, path, fo, true);
                 });
      return;
    }
    if (ins.size() > 1)
      throw Error("isocurv lines takes one input (several are the frames of a series with --time-series)");
    one(ins.front(), out, o, false);
  });
}

} // namespace isocurv::app
