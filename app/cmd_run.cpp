// isocurv run VOLUME -o DIR: the headless pipeline in one go (mesh with curvature, PNG, stats.json).
#include <filesystem>
#include <iostream>
#include <optional>

#include "app/commands.h"
#include "app/line_options_cli.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "io/mesh_file.h"
#include "lines/line_files.h"
#include "viz/render.h"

namespace isocurv::app {

void register_run(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "Volume -> isosurface -> curvature -> DIR/<name>.vtp, DIR/<name>.png and DIR/stats.json");
  cmd->footer("Example: isocurv run lobster.vol --iso 40 -o out/\n"
              "stats.json holds counts, timings_ms per stage, the device, the normals (and their face-normal\n"
              "fallbacks), and area-weighted min/max/mean/percentiles of H, K, k1, k2 without the unreliable vertices.");
  static CommonOptions o;
  static viz::RenderOptions ro;
  static std::string in, dir, format = "vtp";
  cmd->add_option("VOLUME", in, "Volume file")->required();
  cmd->add_option("-o,--output", dir, "Output folder (created if missing)")->required();
  cmd->add_option("--format", format,
                  "Mesh format (vtp or ply: the formats that carry the curvature arrays)")
      ->check(CLI::IsMember({"vtp", "ply"}))
      ->capture_default_str();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o);
  add_render_options(*cmd, ro);
  static LineCli lc;
  add_line_options(*cmd, lc, "");
  cmd->callback([] {
    namespace fs = std::filesystem;
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error& e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    if (is_mesh_path(in)) throw Error(in, "isocurv run takes a volume; use isocurv curvature or render for meshes");
    StageTimer timer;
    Surface s =
        load_surface(in, o, timer);  // fails (no surface, ...) before any output folder is made
    s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, o, timer, &s.normals);
    std::optional<lines::Polylines> poly;  // drawn on the PNG and written as <name>-lines.vtp
    if (lo.lines.any()) {
      const Camera cam = picture_camera(s.mesh, ro.view, ro.width, ro.height);
      poly = lines::join_segments(extract_lines(s.mesh, *s.field, cam, lo, o, timer));
    }
    // The folder is made now, and removed again if it was new and the outputs fail; the outputs
    // appear together or not at all.
    const bool new_folder = !fs::exists(dir);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) throw Error(dir, "cannot create the output folder: " + ec.message());
    struct RemoveIfNew {
      bool armed;
      ~RemoveIfNew() {
        std::error_code ignored;
        if (armed) fs::remove(dir, ignored);  // only when still empty
      }
    } cleanup{new_folder};
    std::string stem = fs::path(in).filename().string();
    stem = stem.substr(0, stem.find('.'));
    const std::string mesh_path = (fs::path(dir) / (stem + "." + format)).string();
    const std::string png_path = (fs::path(dir) / (stem + ".png")).string();
    const std::string stats_path = (fs::path(dir) / "stats.json").string();
    const std::string lines_path = (fs::path(dir) / (stem + "-lines.vtp")).string();
    AtomicFileSet outputs;
    timer.start("write");
    outputs.write(mesh_path,
                  [&](const std::string& tmp) { io::write_mesh(tmp, s.mesh, &*s.field); });
    timer.start("render");
    viz::RenderOptions opts = ro;
    if (opts.title.empty()) opts.title = fs::path(in).filename().string() + "  (" + opts.color + ")";
    outputs.write(png_path, [&](const std::string& tmp) {
      viz::render_png(tmp, s.mesh, *s.field, opts, poly ? &*poly : nullptr);
    });
    if (poly) {
      timer.start("write_lines");
      outputs.write(lines_path, [&](const std::string& tmp) { lines::write_vtp(tmp, *poly); });
    }
    timer.stop();
    nlohmann::json r = surface_report(s);
    r["input"] = in;
    r["mesh"] = mesh_path;
    r["png"] = png_path;
    if (poly) {
      r["lines"] = lines_path;
      r["polylines"] = poly->line_count();
    }
    r["device"] = device_name(o);
    r["timings_ms"] = timer.json();
    outputs.write(stats_path,
                  [&](const std::string& tmp) { write_text_file(tmp, r.dump(2) + "\n"); });
    outputs.commit();
    cleanup.armed = false;
    if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "isosurface at " << s.isovalue << ": " << r["vertices"] << " vertices, " << r["triangles"]
                << " triangles\n  mesh with curvature: " << mesh_path << "\n  picture:             " << png_path
                << "\n  statistics:          " << stats_path << "\n";
      if (poly) std::cout << "  lines:               " << lines_path << "\n";
    }
  });
}

}  // namespace isocurv::app
