// isocurv screen VOLUME|MESH -o image.png [--raw image.vti]: screen-space curvature per pixel
// (Prantl et al. 2017, Mellado et al. 2013) on a G-buffer ray cast from the volume's isosurface
// (no mesh) or rasterised from a mesh file.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "app/commands.h"
#include "app/label_surfaces.h"
#include "app/picture_title.h"
#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "viz/camera_file.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "curvature/auto_scale.h"
#include "core/framing_points.h"
#include "core/mesh_measures.h"
#include "screen/estimate.h"
#include "screen/image_files.h"
#include "screen/rasterise.h"
#include "screen/ray_cast.h"
#include "viz/color_map.h"
#include "viz/quantity.h"
#include "volume/dense_field.h"
#include "volume/load.h"

namespace isocurv::app {
namespace {

/// screen --labels: the labels' indicator reaches this many voxels past their box (the cast's
/// smoothing and gradient stencils read there).
constexpr int kScreenLabelMargin = 8;

/// --smooth as a number of voxels in [0, volume::kMaxSmoothingVoxels]. @throw Error otherwise.
double parse_smoothing(const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != 0 || !(v >= 0 && v <= volume::kMaxSmoothingVoxels))
    throw Error("--smooth: expected auto or a number of voxels from 0 to " +
                format_number(volume::kMaxSmoothingVoxels) + ", not '" + text + "'");
  return v;
}

/// The cast's smoothing in voxels: --smooth's number, or for auto the volume estimator's noise
/// scale (curvature::auto_scale's s1, in voxels) on integer voxel types, 0 on float data.
double screen_smoothing(const std::string& text, const volume::Volume& v, const Mesh& surface, float iso) {
  if (text != "auto") return parse_smoothing(text);
  if (!volume::is_integer_type(v.voxel_type) || surface.positions.empty()) return 0;
  const curvature::ScaleChoice c = curvature::auto_scale(v, surface, iso);
  return std::min(volume::kMaxSmoothingVoxels, c.scale / c.voxel);
}


bool has_ext(const std::string& path, const char* ext) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e == ext;
}

}  // namespace

void register_screen(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "screen",
      "Screen-space curvature per pixel: a volume's isosurface ray cast (no mesh) or a "
      "mesh rasterised, then Prantl's per-pixel shape operator (or Mellado's sphere fit)");
  cmd->footer(
      "Example: isocurv screen gyroid.vdb --color K --size 800x600 --lod on -o gyroid_K.png "
      "--raw gyroid.vti\n"
      "The picture is laid out as isocurv render's (title, legend); the screen-space image fills "
      "its surface part,\nand --raw writes that image's pixels (float arrays H, K, Valid). "
      "Pixels at silhouettes and depth\ndiscontinuities are left out (background). An isovalue "
      "that misses the volume gives an empty image\nand a warning. Sizes up to 8192x8192.");
  static CommonOptions o;
  static ViewSpec view;
  static AnatomicalCli anatomical;
  static screen::PictureOptions po;
  static screen::ScreenOptions so;
  static int width = 1024, height = 768;
  static std::string in, out, raw, estimator = "prantl", lod = "off", depth = "linear",
                                   rule = "report";
  cmd->add_option("VOLUME_OR_MESH", in, "Volume or mesh file")->required();
  cmd->add_option("-o,--output", out, "PNG picture to write")->required();
  cmd->add_option("--raw", raw, "Also write the per-pixel H, K and Valid as VTK image data (.vti)");
  add_common_options(*cmd, o);
  add_label_options(*cmd, o, false);
  add_camera_options(*cmd, view, &anatomical);
  static std::string camera_file;
  cmd->add_option("--camera", camera_file,
                  "Camera JSON saved by the explorer ('k'); replaces --view and the fitting")
      ->check(CLI::ExistingFile)
      ->group("Camera");
  cmd->add_option("--color", po.quantity, "Quantity to colour by: H or K")
      ->check(CLI::IsMember({"H", "K"}))
      ->capture_default_str()
      ->group("Rendering");
  cmd->add_option("--cmap", po.cmap, "Colour map (as isocurv render's)")
      ->check(CLI::IsMember(viz::color_map_names()))
      ->capture_default_str()
      ->group("Rendering");
  cmd->add_option_function<std::vector<std::string>>(
         "--range",
         [](const std::vector<std::string>& v) {
           viz::ColorRange range;
           if (!parse_min_max(v, range))
             throw CLI::ValidationError("--range", "expected MIN,MAX (or MIN MAX) with MIN < MAX");
           po.range = range;
         },
         "Colour exactly this value range (MIN,MAX or MIN MAX)")
      ->expected(1, 2)
      ->group("Rendering");
  cmd->add_option("--percentile", po.clamp_percentile,
                  "The automatic colour range leaves out this percentage of extreme values")
      ->check(CLI::Range(0.0, 49.0))
      ->group("Rendering");
  cmd->add_option("--title", po.title, "Title text (default: input, quantity, isovalue, method)")
      ->group("Rendering");
  cmd->add_option("--unit", po.length_unit, "Length unit for the legend, e.g. mm")
      ->group("Rendering");
  cmd->add_option_function<std::string>(
         "--size",
         [](const std::string& s) {
           int w = 0, h = 0;
           char x = 0;
           if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') ||
               w < 16 || h < 16 || w > screen::kMaxImageSide || h > screen::kMaxImageSide)
             throw CLI::ValidationError("--size",
                                        "expected WIDTHxHEIGHT, each 16..8192, e.g. 800x600");
           width = w, height = h;
         },
         "Picture size WIDTHxHEIGHT (default 1024x768; 16..8192 a side)")
      ->group("Camera");
  cmd->add_option("--estimator", estimator,
                  "prantl (per-pixel shape operator) or mellado "
                  "(sphere fit, H only)")
      ->check(CLI::IsMember({"prantl", "mellado"}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--edges", so.edges, "Edges per pixel triangle: 2 (eq. 17) or 3 (eq. 9-11)")
      ->check(CLI::IsMember({2, 3}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--lod", lod, "Level of detail: wider pixel triangles near the camera")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--lod-size", so.size_max, "The LOD's largest step (pixels)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--fan", so.fan, "LOD triangles around a pixel: 4 (report) or 8 (paper)")
      ->check(CLI::IsMember({4, 8}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--depth", depth,
                  "Depth the LOD and discontinuity rule read: linear "
                  "(eye depth / far) or window (the paper's)")
      ->check(CLI::IsMember({"linear", "window"}))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--discontinuity", rule,
                  "report: a neighbour across a depth jump falls back to "
                  "1 pixel; paper: its triangles are dropped")
      ->check(CLI::IsMember({"report", "paper"}))
      ->capture_default_str()
      ->group("Screen space");
  static std::string smooth_text = "auto";
  cmd->add_option("--smooth", smooth_text,
                  "Smooth the volume by a Gaussian of this deviation (voxels, 0 to 6) before the "
                  "cast: quantised CT steps otherwise show as terraces and moire per pixel. auto: on "
                  "integer voxel types the volume estimator's noise scale (from the noise and the "
                  "edge, as --scale auto measures them), on float data 0")
      ->check(CLI::Validator(
          [](std::string& v) {
            if (v == "auto") return std::string();
            try {
              parse_smoothing(v);
            } catch (const Error& e) {
              return std::string(e.what()).substr(std::string("--smooth: ").size());
            }
            return std::string();
          },
          "auto or 0..6"))
      ->capture_default_str()
      ->group("Screen space");
  cmd->add_option("--mellado-radius", so.mellado_radius, "Mellado's fit radius (pixels)")
      ->check(CLI::Range(1, 32))
      ->capture_default_str()
      ->group("Screen space");
  cmd->callback([] {
    double smooth = 0;  // voxels: screen_smoothing's, for a volume
    if (!has_ext(out, ".png")) throw Error(out, "isocurv screen writes a .png picture");
    require_writable_file(out);  // before any work
    if (!raw.empty() && !has_ext(raw, ".vti")) throw Error(raw, "--raw writes a .vti file");
    if (!raw.empty()) require_writable_file(raw);
    if (o.cap) throw Error("--cap does not apply to isocurv screen (the ray caster reads the box)");
    so.estimator =
        estimator == "mellado" ? screen::ScreenEstimator::mellado : screen::ScreenEstimator::prantl;
    if (so.estimator == screen::ScreenEstimator::mellado && po.quantity == "K")
      throw Error("--estimator mellado gives mean curvature only; use --color H");
    so.lod = lod == "on";
    so.depth = depth == "window" ? screen::DepthMapping::window : screen::DepthMapping::linear;
    so.rule =
        rule == "paper" ? screen::DiscontinuityRule::paper : screen::DiscontinuityRule::report;
    const bool reference = reference_device(o);
    StageTimer timer;
    std::optional<volume::DenseField> cast;
    std::optional<Surface> surf;
    std::vector<Vec3f> normals;
    std::array<double, 6> bounds{};  // a volume's: the box around its surface's bricks
    std::vector<std::array<double, 3>> frame_points;  // a mesh's: its vertices without specks
    float iso = 0;
    std::string format, world_space;
    std::size_t triangles = 0;
    bool empty = false;
    if (is_mesh_path(in) && !o.labelled()) {
      surf = load_surface(in, o, timer);
      prepare_mesh_for_curvature(*surf, in, o);
      // The file's own normals when it has them (isocurv's curvature files: the smooth surface's,
      // from the volume's gradient); else the faces', which on a marching-cubes mesh carry its
      // facets' error and pull the median curvature down (a 64^3 sphere: 0.86 / R, against 1.00
      // with the file's normals; two passes of averaging them gave 0.88, not kept).
      const bool own = surf->field && surf->field->normals.size() == surf->mesh.vertex_count();
      normals = own ? surf->field->normals : area_weighted_normals(surf->mesh);
      triangles = surf->mesh.triangles.size();
      frame_points = framing_points(surf->mesh);
      empty = surf->mesh.triangles.empty();
      if (empty) throw Error(in, "the mesh has no triangles");
      world_space = surface_context(*surf).world_space;
    } else {
      volume::Volume v;
      if (o.labelled()) {  // the picked labels together: their outside, as a picture shows it
        PickedLabels p = pick_labels(in, o, timer);
        timer.start("labels");
        v = labels::labels_indicator(p.map, p.picked, kScreenLabelMargin);
      } else {
        timer.start("load");
        v = volume::load(in, to_load_options(o.volume));
      }
      format = v.format;
      world_space = v.world_space;
      iso = o.iso ? *o.iso : float(v.stats.suggested_isovalue);
      if (!std::isfinite(iso)) throw Error(in, "isovalue must be a finite number");
      // Framed as render frames the same volume: on its isosurface's vertices less the specks.
      timer.start("frame");
      const Mesh surface = extract_surface(v, iso, o);
      frame_points = framing_points(surface);
      smooth = screen_smoothing(smooth_text, v, surface, iso);
      timer.start("index");
      cast.emplace(v);
      if (smooth > 0) {
        timer.start("smooth");
        cast->smooth(smooth);
      }
      timer.start("frame");
      if (!cast->surface_bounds(iso, bounds)) {
        empty = true;
        bounds = cast->bounds;
        if (!o.quiet)
          std::cerr << "isocurv: warning: " << in << ": isovalue " << format_number(iso)
                    << " gives no surface (values " << format_number(v.stats.min) << " to "
                    << format_number(v.stats.max) << "); the image is empty\n";
      }
      timer.stop();
    }
    if (po.title.empty())
      po.title = picture_title(in, po.quantity,
                               cast && !o.labelled() ? std::optional<float>(iso) : std::nullopt,
                               screen::estimator_label(so, cast ? smooth : 0));
    Device* device = reference ? nullptr : &device_for(o);
    screen::GBuffer g;
    screen::ScreenCurvature c;
    // The surface box depends on the legend's labels, which depend on the values: lay out with
    // the widest labels (%.3g of -8.88e+88) unless --range fixes them and compute at that box;
    // when the values' own labels give another box, compute once more at it (so the surface is
    // framed in the box render would frame it in), and centre the image in the final box if
    // the labels moved it again.
    viz::ColorRange range = po.range ? *po.range : viz::ColorRange{-viz::kWidestLegendValue, viz::kWidestLegendValue};
    viz::PictureLayout layout = screen::screen_layout(width, height, po, range);
    const ViewSpec seen_from = resolve_view(view, anatomical, world_space, in);
    const std::optional<Camera> saved =
        camera_file.empty() ? std::nullopt : std::optional<Camera>(viz::load_camera(camera_file));
    Camera camera;
    for (int pass = 0; pass < 3; ++pass) {
      const int sw = layout.surface.x1 - layout.surface.x0,
                sh = layout.surface.y1 - layout.surface.y0;
      if (sw < 1 || sh < 1) throw Error(out, "the picture leaves no room for the surface");
      camera = saved                  ? *saved
               : !frame_points.empty() ? fit_camera_to_points(frame_points, seen_from, double(sw) / sh)
                                       : fit_camera(bounds, seen_from, double(sw) / sh);
      const screen::ViewFrame frame = screen::view_frame(camera, sw, sh);
      timer.start(cast ? "cast" : "rasterise");
      if (cast)
        g = reference ? screen::ray_cast_reference(*cast, iso, frame)
                      : screen::ray_cast(*cast, iso, frame, *device);
      else
        g = screen::rasterise(surf->mesh, normals, frame);
      timer.start("estimate");
      c = reference ? screen::estimate_reference(g, so) : screen::estimate(g, *device, so);
      timer.stop();
      range = screen::screen_range(c, po);
      viz::PictureLayout next =
          screen::screen_layout(width, height, po, range, screen::has_unestimated(g, c));
      const int nw = next.surface.x1 - next.surface.x0, nh = next.surface.y1 - next.surface.y0;
      layout = next;
      if ((nw == sw && nh == sh) || (pass >= 1 && nw >= sw && nh >= sh) || pass == 2) {
        layout.surface.x0 += std::max(0, (nw - sw) / 2),
            layout.surface.y0 += std::max(0, (nh - sh) / 2);
        layout.surface.x1 = layout.surface.x0 + sw, layout.surface.y1 = layout.surface.y0 + sh;
        break;
      }
    }
    timer.start("write");
    AtomicFileSet files;
    files.write(
        out, [&](const std::string& tmp) { screen::write_picture(tmp, g, c, layout, po, range); });
    if (!raw.empty())
      files.write(raw, [&](const std::string& tmp) { screen::write_raw(tmp, c, &layout); });
    files.commit();
    timer.stop();
    std::vector<float> hv, kv;
    for (std::size_t i = 0; i < c.valid.size(); ++i)
      if (c.valid[i]) hv.push_back(c.H[i]), kv.push_back(c.K[i]);
    auto median = [](std::vector<float> v) -> nlohmann::json {
      if (v.empty()) return nullptr;
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    };
    if (o.json) {
      nlohmann::json r;
      r["input"] = in;
      r["output"] = out;
      if (!raw.empty()) r["raw"] = raw;
      if (cast) r["isovalue"] = iso;
      if (surf) r["triangles"] = triangles;
      r["producer"] = cast ? "ray cast" : "rasterised mesh";
      r["estimator"] = screen::estimator_label(so);
      if (cast) r["smoothing_voxels"] = smooth;
      r["picture"] = {{"width", width}, {"height", height}};  // the PNG written
      r["image"] = {{"width", c.width}, {"height", c.height}};  // the cast part (--raw's pixels)
      r["surface_pixels"] = g.valid_count();
      r["estimated_pixels"] = hv.size();
      r["coverage"] = double(g.valid_count()) / std::max<std::size_t>(1, g.pixels());
      r["median_H"] = median(hv);
      if (so.estimator == screen::ScreenEstimator::prantl) r["median_K"] = median(kv);
      r["empty"] = empty;
      r["device"] = device_name(o);
      r["timings_ms"] = timer.json();
      std::cout << r.dump(2) << "\n";
    } else if (!o.quiet) {
      std::cout << "wrote " << out << " (" << width << "x" << height << ")"
                << (raw.empty() ? "" : " and " + raw) << ": the surface's part cast at " << c.width
                << "x" << c.height << ", " << hv.size() << " pixels estimated\n";
    }
  });
}

}  // namespace isocurv::app
