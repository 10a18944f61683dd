// isocurv view VOLUME: the interactive explorer (isovalue slider, curvature colours); with
// --time-series a series of volumes or of mesh files (a flipbook, a deforming mesh, a .pvd).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "ao/method.h"
#include "app/batch.h"
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
#include "io/pvd_collection.h"
#include "lines/extract.h"
#include "lines/reference.h"
#include "mc/extract.h"
#include "screen/estimate.h"
#include "screen/image_files.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "viz/explorer.h"
#include "viz/explorer_script.h"
#include "volume/dense_field.h"

namespace isocurv::app {
namespace {

bool is_pvd_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".pvd";
}

/// The frames a .pvd collection lists (its files, resolved, and its times), labelled by file
/// stem (app/batch.h, file_stem).
std::vector<SeriesFrame> pvd_frames(const std::string& path) {
  std::vector<SeriesFrame> frames;
  for (const io::PvdFrame& f : io::read_pvd(path)) {
    frames.push_back({f.file, "", file_stem(f.file, "frame"), f.time});
  }
  if (frames.empty()) throw Error(path, "the collection lists no frame");
  return frames;
}

}  // namespace

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
      "with --time-series FILES... a time slider, and space plays / pauses the frames: volumes\n"
      "(cut at the slider's isovalue) or mesh files (a flipbook, what deform -o writes, or a .pvd;\n"
      "no isovalue slider; each array's colour range is the first frame's). Needs an X display.");
  static CommonOptions o;
  static RenderCli ro;
  static std::vector<std::string> ins;
  static SeriesCli series;
  static std::string screenshots = "isocurv-screenshot", camera_out = "isocurv-camera.json",
                         surface_out = "isocurv-surface.vtp";
  cmd->add_option("VOLUME", ins,
                  "Volume file, or mesh file (.vtp .ply .obj .stl; several, a quoted glob, a .pvd "
                  "collection or a multi-grid .vdb with --time-series: the frames of a series)")
      ->required();
  static std::string script;  // scripted runs (viz/explorer_script.h), demos and the tests
  cmd->add_option("--script", script,
                  "Run the actions of FILE, one a line (iso V, key C, type TEXT, screenshot PATH, "
                  "status PATH, frame K, resize W H, wait), then close; headless when there is no "
                  "display (docs/pictures.md, Scripted runs)");
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
    // The frames (one without --time-series): volumes, or mesh files.
    if (series.enabled && ins.size() > 1 && std::any_of(ins.begin(), ins.end(), is_pvd_path))
      throw Error("--time-series takes one .pvd collection, or files, not both");
    const std::vector<SeriesFrame> frames =
        series.enabled && is_pvd_path(ins.front()) ? pvd_frames(ins.front())
        : series.enabled ? series_frames(ins, o.volume.grid, series.time_step)
                         : std::vector<SeriesFrame>{{ins.front(), "", "", 0}};
    const bool meshes = is_mesh_path(frames.front().path);
    for (const SeriesFrame& f : frames)
      if (is_mesh_path(f.path) != meshes)
        throw Error(f.path, std::string("the frames of a series are all volumes or all mesh files, ") +
                                (meshes ? "and this is not a mesh file" : "and this is a mesh file"));
    static std::string in;
    in = frames.front().path;
    viz::ExplorerSetup setup;
    if (!script.empty()) setup.script = viz::read_explorer_script(script);
    setup.screenshot_prefix = screenshots;
    setup.camera_path = camera_out;
    setup.surface_path = surface_out;
    if (frames.size() > 1) {
      setup.frames = static_cast<int>(frames.size());
      setup.frame_label = [frames](int k) {
        return frames[k].label + ", t = " + format_number(frames[k].time);
      };
    }
    // The volume frame shown (its volume and mesher; volumes only).
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
    if (meshes) {
      // A mesh series: each frame's file read when it is shown, with its curvature arrays, or
      // estimated (as render does) when it carries none or not what the lines need. No isovalue;
      // each array's colour range is the first frame's, so that playing does not flicker.
      struct MeshFrames {
        int frame = 0;                     // the frame set_frame made current
        std::optional<viz::Surface> first;  // frame 0, read below, shown first
        std::string estimator;             // of the frame shown, for the title
      };
      auto mf = std::make_shared<MeshFrames>();
      const bool lines_wanted = lo.lines.any();
      auto read_frame = [mf, lines_wanted](const std::string& path, bool quiet, SurfaceContext* context) {
        CommonOptions fo = o;
        fo.quiet = o.quiet || quiet;  // a welding note or a warning once, not every frame
        StageTimer timer;
        auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        const auto t0 = std::chrono::steady_clock::now();
        Surface s = load_surface(path, fo, timer);
        const auto t1 = std::chrono::steady_clock::now();
        const std::size_t nv = s.mesh.positions.size();
        const bool estimate = fo.flip || !s.field || s.field->H.size() != nv ||
                              (lines_wanted && (s.field->dir1.size() != nv || s.field->dcurv.size() != nv));
        if (estimate)
          reestimate_keeping_extras(s, path, fo, timer);
        else if (!fo.ao.empty())
          apply_ao(s.mesh, *s.field, nullptr, 0, fo, timer);  // --ao-method on the file's curvature
        const auto t2 = std::chrono::steady_clock::now();
        const SurfaceContext c = surface_context(s);
        if (context) *context = c;
        mf->estimator = with_ao(estimate                    ? estimator_title(s.estimator)
                                : c.file_estimator.empty() ? "curvature from the file"
                                                           : "from the file: " + c.file_estimator,
                                o);
        viz::Surface out{std::move(s.mesh), std::move(*s.field), ms(t0, t2), ""};
        out.detail = "read " + std::to_string(int(ms(t0, t1))) + " ms, curvature " +
                     (estimate ? "estimated " + std::to_string(int(ms(t1, t2))) + " ms" : "from the file");
        return out;
      };
      SurfaceContext context;
      mf->first = read_frame(frames.front().path, false, &context);  // errors before any window
      setup.has_isovalue = false;
      setup.shared_color_range = true;
      if (frames.size() > 1)
        setup.set_frame = [mf, frames](int k) {
          mf->frame = k;
          in = frames[k].path;
        };
      setup.surface = [mf, frames, read_frame](float) {
        if (mf->first) {
          viz::Surface s = std::move(*mf->first);
          mf->first.reset();
          return s;
        }
        return read_frame(frames[mf->frame].path, true, nullptr);
      };
      setup.view = render_options_for(ro, in, context, mf->estimator, &mf->first->field);
      if (ro.title.empty())
        setup.title_for = [mf](float, const std::string& quantity) {
          return picture_title(in, quantity, std::nullopt, mf->estimator);
        };
    } else {
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
      if (frames.size() > 1) setup.set_frame = [load_frame](int k) { load_frame(k, nullptr); };
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
      setup.screen.bounds = [cur](float value, std::array<double, 6>& b) {
        return cur->field().surface_bounds(value, b);
      };
    }
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
    // Screen-space mode: the volume's isosurface ray cast per pixel (or the mesh shown, a file
    // opened or a mesh series' frame, rasterised), then Prantl's per-pixel estimator, as isocurv
    // screen does.
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
    if (ro.title.empty())
      setup.screen.title_for = [meshes](float value, const std::string& quantity) {
        return picture_title(in, quantity, meshes ? std::nullopt : std::optional<float>(value),
                             screen::estimator_label(so, meshes ? 0 : screen_smooth));
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
