// isocurv run VOLUME -o DIR: the headless pipeline in one go (mesh with curvature, PNG, stats.json).
#include <filesystem>
#include <iostream>
#include <optional>

#include "app/batch.h"
#include "app/commands.h"
#include "app/distributed.h"
#include "dist/world.h"
#include "app/label_surfaces.h"
#include "app/line_options_cli.h"
#include "app/pipeline.h"
#include "app/series.h"
#include "app/shared_pictures.h"
#include "app/picture_title.h"
#include "app/render_options_cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "io/mesh_file.h"
#include "lines/line_files.h"
#include "viz/camera_file.h"
#include "viz/direction_glyphs.h"
#include "viz/render.h"

namespace isocurv::app {

namespace {

/// One volume -> the folder `dir` with <stem>.<format> (every curvature array), <stem>.png,
/// stats.json and, with --lines, <stem>-lines.vtp, written together or not at all; returns the
/// stats.json report. With `shared` (a series' --range shared), the picture and the lines are
/// left to shared->draw() and only noted here.
nlohmann::json run_one(const std::string& in, const std::string& dir, const CommonOptions& o,
                       const RenderCli& ro, const lines::Options& lo, const std::string& format,
                       SharedPictures* shared = nullptr) {
  namespace fs = std::filesystem;
  StageTimer timer;
  // Fails (no surface, ...) before any output folder is made.
  // Under mpirun: the ranks extract the surface and its curvature together, rank 0 goes on alone.
  // Label surfaces are not divided among ranks: every rank would compute and write all of them.
  if (o.labelled() && dist::World::get().size() > 1)
    throw Error("--labels and --label do not run distributed (run them without mpirun)");
  std::optional<Surface> on_zero = o.labelled() ? load_label_surfaces(in, o, timer, true)
                                                : surface_for_rank_zero(in, o, timer, DistributedWork::curvature);
  if (!on_zero) return nlohmann::json::object();
  Surface& s = *on_zero;
  if (!o.labelled() && !s.field)
    s.field = estimate_curvature(s.mesh, s.volume ? &*s.volume : nullptr, s.isovalue, o, timer,
                                 &s.normals, &s.estimator);
  std::optional<lines::Polylines> poly;  // drawn on the PNG and written as <name>-lines.vtp
  // The folder is made now, and removed again if it was new and the outputs fail; the outputs
  // appear together or not at all.
  // (Also when the run is interrupted: NewFolder.)
  const NewFolder folder(dir);
  const std::string stem = file_stem(in, "input");
  const std::string mesh_path = (fs::path(dir) / (stem + "." + format)).string();
  const std::string png_path = (fs::path(dir) / (stem + ".png")).string();
  const std::string stats_path = (fs::path(dir) / "stats.json").string();
  const std::string lines_path = (fs::path(dir) / (stem + "-lines.vtp")).string();
  AtomicFileSet outputs;
  timer.start("write");
  std::uint64_t mesh_bytes = 0;
  outputs.write(mesh_path, [&](const std::string& tmp) {
    const io::Metadata context = context_metadata(s, in, ro.opts.length_unit);
    io::write_mesh(tmp, s.mesh, &*s.field, o.compress, &context, &s.label_cells);
    mesh_bytes = file_bytes(tmp);
  });
  timer.start("render");
  const viz::RenderOptions opts =
      render_options_for(ro, in, surface_context(s), with_ao(estimator_title(s.estimator), o),
                         &*s.field);
  viz::LinesForCamera lines_for;
  if (lo.lines.any() && !shared)
    lines_for = [&](const Camera& cam) {
      poly = lines::join_segments(extract_lines(s.mesh, *s.field, cam, lo, o, timer));
      return *poly;
    };
  if (shared)
    shared->add({mesh_path, png_path, opts, lo.lines.any() ? lines_path : ""}, s.mesh, *s.field);
  else
    outputs.write(png_path, [&](const std::string& tmp) {
      viz::render_png(tmp, s.mesh, *s.field, opts, lines_for);
    });
  if (!ro.dirs_out.empty())
    outputs.write(ro.dirs_out, [&](const std::string& tmp) {
      viz::write_glyphs(tmp, viz::direction_glyphs(s.mesh, *s.field, viz::glyph_options(opts)));
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
  if (shared) r["picture"] = "drawn after the last frame, with the series' shared colour range and camera";
  if (shared && lo.lines.any()) r["lines"] = lines_path;
  r["mesh_bytes"] = mesh_bytes;
  r["compression"] = io::to_string(o.compress);
  if (poly) {
    r["lines"] = lines_path;
    r["polylines"] = poly->line_count();
  }
  r["device"] = device_name(o);
  r["programs"] = program_report();
  r["timings_ms"] = timer.json();
  outputs.write(stats_path,
                [&](const std::string& tmp) { write_text_file(tmp, r.dump(2) + "\n"); });
  outputs.commit();
  return r;
}

}  // namespace

void register_run(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "Volume -> isosurface -> curvature -> DIR/<name>.vtp, DIR/<name>.png and DIR/stats.json");
  cmd->footer("Example: isocurv run lobster.vol --iso 40 -o out/\n"
              "Series: isocurv run --time-series 'frames_*.nhdr' -o anim/  (anim/<frame>/, anim/series.pvd for ParaView)\n"
              "stats.json holds counts, timings_ms per stage, the device, the normals (and their face-normal\n"
              "fallbacks), and area-weighted min/max/mean/percentiles of H, K, k1, k2 without the unreliable vertices.");
  static CommonOptions o;
  static RenderCli ro;
  static BatchCli b;
  static SeriesCli series;
  static std::string dir, format = "vtp";
  add_batch_options(*cmd, b, "VOLUME", "Volume file", {});
  cmd->add_option("-o,--output", dir, "Output folder (created if missing)")->required();
  cmd->add_option("--format", format,
                  "Mesh format (vtp or ply: the formats that carry the curvature arrays)")
      ->check(CLI::IsMember({"vtp", "ply"}))
      ->capture_default_str();
  add_common_options(*cmd, o, false);
  add_curvature_options(*cmd, o);
  add_ao_options(*cmd, o);
  add_compress_option(*cmd, o);
  add_label_options(*cmd, o, false);
  add_render_options(*cmd, ro);
  static LineCli lc;
  add_line_options(*cmd, lc, "");
  add_series_options(*cmd, series);
  cmd->callback([] {
    namespace fs = std::filesystem;
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error& e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    require_lines_supported(lo.lines, o);
    for (const std::string& input : b.inputs)
      if (is_mesh_path(input))
        throw Error(input, "isocurv run takes a volume; use isocurv curvature or render for meshes");
    if (!ro.dirs_out.empty() && !ro.opts.dirs) throw Error(ro.dirs_out, "--dirs-out needs --dirs");
    if (!ro.dirs_out.empty()) viz::check_glyphs_path(ro.dirs_out);
    // A bad --camera fails early, before any batch entry or output folder.
    if (!ro.camera_file.empty()) viz::load_camera(ro.camera_file);
    if (series.enabled) {
      if (!ro.dirs_out.empty())
        throw Error(ro.dirs_out, "--dirs-out names one file: not with --time-series");
      require_series_cli(b, o);
      if (format != "vtp")
        throw Error("--format " + format + ": a time series writes .vtp frames (ParaView's .pvd reads XML files)");
      SharedPictures shared(ro);
      SharedPictures* pictures = shared.active() ? &shared : nullptr;
      // The pictures are drawn once every frame is known, also when a bad frame stopped the
      // series (the frames written keep their pictures).
      auto draw = [&] {
        if (!pictures) return;
        const std::vector<SharedPictureFailure> failures = shared.draw(
            [&](const Mesh& mesh, const curvature::CurvatureField& field, const Camera& cam) {
              StageTimer ignored;
              return lines::join_segments(extract_lines(mesh, field, cam, lo, o, ignored));
            });
        for (const SharedPictureFailure& f : failures) std::cerr << "isocurv: " << f.message << "\n";
        if (!failures.empty())
          throw Error(std::to_string(failures.size()) + " pictures of the series failed (listed above)");
      };
      try {
        run_series(b.inputs, series, {"run", dir, /*folder_per_frame=*/true, format}, o,
                   [&lo, pictures](const SeriesFrame& f, CommonOptions& fo, const std::string& path) {
                     return run_one(f.path, path, fo, ro, lo, format, pictures);
                   });
      } catch (const Error&) {
        try {
          draw();
        } catch (const Error&) {
        }
        throw;
      }
      draw();
      return;
    }
    if (lo.lines.any() && (b.inputs.size() > 1 || b.iso.find(',') != std::string::npos))
      throw Error("--lines: one input at one isovalue (not in batches)");
    if (run_as_batch(b, o, BatchKind::run, dir, &ro, format)) return;
    const std::string& in = b.inputs.front();
    require_folder_name(dir, "run");  // before any work
    const nlohmann::json r = run_one(in, dir, o, ro, lo, format);
    if (dist::World::get().rank() != 0) {
    } else if (o.json) {
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      if (r.contains("labels"))
        std::cout << r["labels"].size() << " label surfaces";
      else
        std::cout << "isosurface at " << r.value("isovalue", 0.0f);
      std::cout << ": " << r["vertices"] << " vertices, " << r["triangles"]
                << " triangles\n  mesh with curvature: " << r["mesh"].get<std::string>()
                << "\n  picture:             " << r["png"].get<std::string>()
                << "\n  statistics:          " << (fs::path(dir) / "stats.json").string() << "\n";
      if (r.contains("lines"))
        std::cout << "  lines:               " << r["lines"].get<std::string>() << "\n";
    }
  });
}

}  // namespace isocurv::app
