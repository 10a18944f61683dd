// isocurv view VOLUME: the interactive explorer (isovalue slider, curvature colours).
#include <chrono>
#include <iostream>
#include <memory>

#include "ao/method.h"
#include "app/commands.h"
#include "app/line_options_cli.h"
#include "app/picture_title.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "app/series.h"
#include "core/error.h"
#include "core/mesh_measures.h"
#include "curvature/estimate.h"
#include "io/mesh_file.h"
#include "lines/extract.h"
#include "lines/reference.h"
#include "mc/extract.h"
#include "screen/estimate.h"
#include "screen/image_files.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "viz/explorer.h"
#include "volume/dense_field.h"

namespace isocurv::app {

void register_view(CLI::App& app) {
  auto* cmd = app.add_subcommand("view", "Explore a volume interactively: isovalue slider, surface coloured by curvature");
  cmd->footer(
      "Example: isocurv view headsq.raw --dims 64 64 93 --type int16 --iso 500\n"
      "Keys: c cycles the colour through every point array of the surface (H ... AO, then\n"
      "extras such as H_s2 or an opened mesh's LBE, H_ii), a toggles AO, d toggles direction\n"
      "glyphs, l toggles the feature lines (--lines; they follow the camera and the isovalue),\n"
      "v cycles the views, r resets the camera, i types an isovalue, o opens a mesh file, w saves\n"
      "the surface shown, k saves the camera (for render --camera), s saves a screenshot, x\n"
      "switches to screen-space curvature (ray cast per pixel, no mesh; the slider re-casts) and\n"
      "back, q quits;\n"
      "with --time-series FILES... a time slider, and space plays / pauses the frames. Needs an X\n"
      "display.");
  static CommonOptions o;
  static RenderCli ro;
  static std::vector<std::string> ins;
  static SeriesCli series;
  static std::string screenshots = "isocurv-screenshot", camera_out = "isocurv-camera.json",
                         surface_out = "isocurv-surface.vtp";
  cmd->add_option("VOLUME", ins,
                  "Volume file (several, a quoted glob or a multi-grid .vdb with --time-series: "
                  "the frames of a series)")
      ->required();
  cmd->add_option("--screenshots", screenshots, "'s' writes PREFIX-NNN.png")->capture_default_str();
  cmd->add_option("--camera-out", camera_out, "'k' writes the camera here")->capture_default_str();
  cmd->add_option("--surface-out", surface_out, "The path 'w' proposes for the surface (.vtp or .ply)")
      ->capture_default_str();
  add_common_options(*cmd, o);
  add_curvature_options(*cmd, o);
  add_ao_options(*cmd, o);
  add_render_options(*cmd, ro, false);
  static LineCli lc;
  add_line_options(*cmd, lc, "contours,suggestive");
  static bool show_lines = false;
  cmd->add_flag("--show-lines", show_lines, "Start with the lines on (else press l)")->group("Lines");
  add_series_options(*cmd, series);
  static bool screen_start = false;
  static std::string screen_lod = "off";
  static screen::ScreenOptions so;
  static double screen_smooth = 0;
  cmd->add_option("--screen-smooth", screen_smooth,
                  "Screen-space mode: smooth the volume by a Gaussian of this deviation (voxels, "
                  "up to 6) before casting (quantised CT steps otherwise show as terraces)")
      ->check(CLI::Range(0.0, volume::kMaxSmoothingVoxels))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_flag("--screen", screen_start,
                "Start in screen-space mode (x): curvature per pixel of the ray-cast isosurface, "
                "nothing extracted until x leaves it")
      ->group("Screen space");
  cmd->add_option("--screen-edges", so.edges, "Screen-space mode: edges per pixel triangle, 2 or 3")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--screen-lod", screen_lod,
                  "Screen-space mode: level of detail (wider pixel triangles near the camera)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->callback([] {
    so.lod = screen_lod == "on";
    lines::Options lo;
    try {
      lo = line_options(lc);
    } catch (const Error& e) {
      throw CLI::ValidationError("--lines", e.what());
    }
    require_lines_supported(lo.lines, o);
    if (ins.size() > 1 && !series.enabled)
      throw Error("isocurv view takes one volume (several are the frames of a series with --time-series)");
    // The frames (one without --time-series); the current one's volume and mesher.
    const std::vector<SeriesFrame> frames =
        series.enabled ? series_frames(ins, o.volume.grid, series.time_step)
                       : std::vector<SeriesFrame>{{ins.front(), "", "", 0}};
    static std::string in;
    in = frames.front().path;
    struct Current {
      std::shared_ptr<volume::Volume> vol;
      std::shared_ptr<mc::Mesher> mesher;
      std::shared_ptr<volume::DenseField> dense;  // the ray caster's samples, made on first use
      const volume::DenseField& field() {
        if (!dense) {
          dense = std::make_shared<volume::DenseField>(*vol);
          dense->smooth(screen_smooth);
        }
        return *dense;
      }
    };
    auto cur = std::make_shared<Current>();
    auto load_frame = [frames, cur](int k, float* iso) {
      CommonOptions fo = o;
      if (!frames[k].grid.empty()) fo.volume.grid = frames[k].grid;
      if (iso == nullptr) fo.iso.reset();  // a later frame: its range is checked by extraction
      StageTimer timer;
      float ignored = 0;
      auto vol = std::make_shared<volume::Volume>(load_volume(frames[k].path, fo, timer, iso ? iso : &ignored));
      // The OpenCL mesher keeps its per-block ranges between slider moves; the reference re-reads
      // the whole volume each time (slow, but it needs no OpenCL).
      std::shared_ptr<mc::Mesher> mesher;
      if (!reference_device(o)) mesher = std::make_shared<mc::Mesher>(*vol, device_for(o));
      cur->vol = vol;
      cur->mesher = mesher;
      cur->dense.reset();
      in = frames[k].path;
    };
    float iso = 0;
    load_frame(0, &iso);
    auto vol = cur->vol;
    viz::ExplorerSetup setup;
    if (frames.size() > 1) {
      setup.frames = static_cast<int>(frames.size());
      setup.set_frame = [load_frame](int k) { load_frame(k, nullptr); };
      setup.frame_label = [frames](int k) {
        return frames[k].label + ", t = " + format_number(frames[k].time);
      };
    }
    setup.isovalue = iso;
    setup.min_value = static_cast<float>(vol->stats.min);
    setup.max_value = static_cast<float>(vol->stats.max);
    SurfaceContext context;
    context.isovalue = iso;
    context.length_unit = vol->length_unit;
    context.world_space = vol->world_space;
    setup.view = render_options_for(ro, in, context, with_ao(estimator_title(o), o));
    if (ro.title.empty())
      setup.title_for = [](float value, const std::string& quantity) {
        return picture_title(in, quantity, value, with_ao(estimator_title(o), o));
      };
    vol.reset();  // the frame shown is held by cur (and replaced by set_frame)
    setup.screenshot_prefix = screenshots;
    setup.camera_path = camera_out;
    setup.surface_path = surface_out;
    setup.save_surface = [](const std::string& path, const Mesh& mesh, const curvature::CurvatureField& field) {
      require_curvature_format(path);
      io::write_mesh(path, mesh, &field);
    };
    setup.open_mesh = [](const std::string& path) {
      if (!is_mesh_path(path)) throw Error(path, "not a mesh file (.vtp .ply .obj .stl)");
      CommonOptions mesh_options;  // the mesh's own defaults: normals from its faces
      mesh_options.device = o.device;
      mesh_options.quiet = true;
      mesh_options.ao_scale = o.ao_scale;
      // the curvature formulas apply to a mesh; a ray cast needs the volume, so a mesh gets griffin
      if (!ao::needs_volume(*ao::method_from_name(o.ao.empty() ? "griffin" : o.ao))) {
        mesh_options.ao = o.ao;
        mesh_options.hattori_half = o.hattori_half;
      }
      StageTimer ignored;
      Surface s = load_surface(path, mesh_options, ignored);
      if (!s.field || s.field->H.size() != s.mesh.positions.size())
        reestimate_keeping_extras(s, path, mesh_options, ignored);
      return viz::Surface{std::move(s.mesh), std::move(*s.field), 0, "opened " + path};
    };
    setup.surface = [cur](float value) {
      const std::shared_ptr<volume::Volume> vol = cur->vol;
      const std::shared_ptr<mc::Mesher> mesher = cur->mesher;
      const auto t0 = std::chrono::steady_clock::now();
      mc::Options mo;
      mo.cap = o.cap;
      mo.snap = o.snap;
      mc::ExtractTimings et;
      viz::Surface out;
      out.mesh = mesher ? mesher->extract(value, mo, &et) : extract_surface(*vol, value, o);
      const auto t1 = std::chrono::steady_clock::now();
      StageTimer ignored;  // the explorer shows its own timings
      out.field = estimate_curvature(out.mesh, vol.get(), value, o, ignored);
      const auto t2 = std::chrono::steady_clock::now();
      auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
      out.update_ms = ms(t0, t2);
      out.detail = "extract " + std::to_string(int(ms(t0, t1))) + " ms (" + std::to_string(et.bricks) +
                   " bricks), curvature " + std::to_string(int(ms(t1, t2))) + " ms";
      return out;
    };
    // Screen-space mode: the volume's isosurface ray cast per pixel (or the mesh file shown
    // rasterised), then Prantl's per-pixel estimator, as isocurv screen does.
    setup.screen.start_on = screen_start;
    setup.screen.image = [cur](float value, const viz::Surface* shown, const Camera& camera, int w,
                               int h) {
      const auto t0 = std::chrono::steady_clock::now();
      const screen::ViewFrame frame = screen::view_frame(camera, w, h);
      const bool reference = reference_device(o);
      screen::GBuffer g;
      if (shown) {
        const bool has_normals = shown->field.normals.size() == shown->mesh.positions.size();
        g = screen::rasterise(
            shown->mesh, has_normals ? shown->field.normals : area_weighted_normals(shown->mesh),
            frame);
      } else {
        const volume::DenseField& field = cur->field();
        g = reference ? screen::ray_cast_reference(field, value, frame)
                      : screen::ray_cast(field, value, frame, device_for(o));
      }
      const auto t1 = std::chrono::steady_clock::now();
      screen::ScreenCurvature c =
          reference ? screen::estimate_reference(g, so) : screen::estimate(g, device_for(o), so);
      const auto t2 = std::chrono::steady_clock::now();
      auto ms = [](auto a, auto b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
      };
      viz::ScreenImage img =
          screen::explorer_image(g, std::move(c), so.estimator == screen::ScreenEstimator::prantl);
      img.update_ms = ms(t0, t2);
      img.detail = std::string(shown ? "rasterise " : "cast ") + std::to_string(int(ms(t0, t1))) +
                   " ms, estimate " + std::to_string(int(ms(t1, t2))) + " ms";
      return img;
    };
    setup.screen.bounds = [cur](float value, std::array<double, 6>& b) {
      return cur->field().surface_bounds(value, b);
    };
    if (ro.title.empty())
      setup.screen.title_for = [](float value, const std::string& quantity) {
        return picture_title(in, quantity, value, screen::estimator_label(so, screen_smooth));
      };
    if (lo.lines.any()) {
      setup.show_lines = show_lines;
      setup.lines = [lo](const viz::Surface& s, const Camera& cam, bool surface_changed) {
        const lines::Segments segs =
            reference_device(o) ? lines::extract_reference(s.mesh, s.field, cam, lo)
                                : lines::extract(s.mesh, s.field, cam, lo, device_for(o), nullptr, surface_changed);
        return lines::join_segments(segs);
      };
    }
    viz::run_explorer(setup);
  });
}

}  // namespace isocurv::app
