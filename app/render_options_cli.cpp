#include "app/render_options_cli.h"

#include <cmath>
#include <cstdio>

#include "app/picture_title.h"
#include "core/error.h"
#include "features/features.h"
#include "viz/camera_file.h"
#include "viz/color_map.h"
#include "viz/quantity.h"

namespace isocurv::app {

bool parse_min_max(const std::vector<std::string>& v, viz::ColorRange& out) {
  if (v.empty() || v.size() > 2) return false;
  std::string text = v[0];
  if (v.size() == 2) text += "," + v[1];
  double lo = 0, hi = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &lo, &hi, &tail) != 2 || !std::isfinite(lo) ||
      !std::isfinite(hi) || !(lo < hi))
    return false;
  out = viz::ColorRange{lo, hi};
  return true;
}

void add_render_options(CLI::App& cmd, RenderCli& r, bool files) {
  viz::RenderOptions& opts = r.opts;
  cmd.add_option("--color", opts.color,
                 "Point array to colour by: H, K, k1, k2, ShapeIndex, Curvedness, AO, or any other "
                 "array of the mesh (H_s2, H_ii, LBE_r0.3, ...; an unknown name lists them)")
      ->capture_default_str()
      ->group("Rendering");
  cmd.add_option(
         "--cmap", opts.cmap,
         "Colour map: auto (diverging for H K k1 k2 ShapeIndex and arrays named after them, grey "
         "for AO, viridis for the others), diverging (colour-blind-safe blue - light grey at zero "
         "- red), viridis "
         "(perceptually uniform), grey, bgr (the papers' blue-green-red)")
      ->check(CLI::IsMember(viz::color_map_names()))
      ->capture_default_str()
      ->group("Rendering");
  cmd.add_option_function<std::vector<std::string>>(
         "--range",
         [&r](const std::vector<std::string>& v) {
           const std::string bad = "expected shared, each, MIN,MAX or MIN MAX with MIN < MAX";
           if (v.size() == 1 && (v[0] == "shared" || v[0] == "each")) {
             r.range_mode = v[0];
             r.opts.range.reset();
             return;
           }
           viz::ColorRange range;
           if (!parse_min_max(v, range)) throw CLI::ValidationError("--range", bad);
           r.opts.range = range;
         },
         "Colour range: MIN,MAX (or MIN MAX) exactly; shared (the default) gives the pictures of "
         "a sweep, batch or series one range from all their values, and one camera; each: every "
         "picture its own (from its values, see --percentile)")
      ->expected(1, 2)
      ->group("Rendering");
  cmd.add_option("--percentile", opts.clamp_percentile,
                 "The automatic colour range leaves out this percentage of extreme values (0..49)")
      ->check(CLI::Range(0.0, 49.0))
      ->capture_default_str()
      ->group("Rendering");
  cmd.add_option_function<std::string>(
         "--shading",
         [&opts](const std::string& s) {
           try {
             opts.shading = viz::parse_shading(s);
           } catch (const Error& e) {
             throw CLI::ValidationError("--shading", e.what());
           }
         },
         "lambert (default), ambient-ao (the ambient term times the curvature AO, as Griffin et "
         "al.; "
         "diffuse light kept) or both (AO darkens ambient and diffuse)")
      ->group("Rendering");
  cmd.add_flag_callback(
         "--ao", [&opts] { opts.shading = viz::Shading::ambient_ao; },
         "Same as --shading ambient-ao")
      ->group("Rendering");
  cmd.add_flag("--dirs", opts.dirs,
               "Draw principal directions on a subsample of vertices (dir1 white, dir2 black, each "
               "with a "
               "halo of the other)")
      ->group("Rendering");
  cmd.add_option("--dirs-count", opts.dirs_count,
                 "About this many direction glyphs over the surface (default: one per 36x36 pixels "
                 "of the image, never denser than 2.5 mean edges)")
      ->check(CLI::Range(1, 1000000))
      ->group("Rendering");
  cmd.add_option("--dirs-length", opts.dirs_length,
                 "Glyph length in world units (default: 0.7 x their spacing)")
      ->check(CLI::PositiveNumber)
      ->group("Rendering");
  if (files)
    cmd.add_option("--dirs-out", r.dirs_out,
                   "Also write the direction glyphs to this .vtp (line cells)")
        ->group("Rendering");
  cmd.add_option_function<std::string>(
         "--size",
         [&opts](const std::string& s) {
           int w = 0, h = 0;
           char x = 0;
           if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') ||
               w < 16 || h < 16 || w > 8192 || h > 8192)
             throw CLI::ValidationError("--size",
                                        "expected WIDTHxHEIGHT, each 16..8192, e.g. 1024x768");
           opts.width = w;
           opts.height = h;
         },
         "Image size WIDTHxHEIGHT (default 1024x768)")
      ->group("Rendering");
  cmd.add_option("--title", r.title, "Title text (default: file, quantity, isovalue, estimator)")
      ->group("Rendering");
  cmd.add_option("--unit", opts.length_unit,
                 "The volume's length unit for the legend, e.g. mm (default: 'length': 1/length)")
      ->group("Rendering");
  add_camera_options(cmd, opts.view, &r.anatomical);
  cmd.add_option("--camera", r.camera_file,
                 "Camera JSON saved by the explorer ('k'); replaces --view and the fitting")
      ->check(CLI::ExistingFile)
      ->group("Camera");
}

void add_camera_options(CLI::App& cmd, ViewSpec& view, AnatomicalCli* anatomical) {
  cmd.add_option_function<std::string>(
         "--view",
         [&view, anatomical](const std::string& s) {
           if (anatomical) anatomical->view_given = true;
           if (anatomical && is_anatomical_view(s)) {
             anatomical->view = s;
             return;
           }
           try {
             view.view = parse_named_view(s);
           } catch (const Error& e) {
             throw CLI::ValidationError(
                 "--view",
                 std::string(e.what()) +
                     (anatomical ? "; for NIfTI, MetaImage and NRRD (with a space) volumes also "
                                   "anterior, posterior, left, right, superior or inferior"
                                 : ""));
           }
         },
         std::string("Viewpoint: iso (three-quarter view from above, the default), or +x -x +y -y "
                     "+z -z (the camera on that side of the centre, looking at it)") +
             (anatomical ? "; NIfTI (world RAS), MetaImage (world LPS) and NRRD volumes with a "
                           "space field also take anterior, posterior, left, right, superior, "
                           "inferior, and default to a three-quarter view from the front with "
                           "superior up"
                         : ""))
      ->group("Camera");
  cmd.add_option_function<std::string>(
         "--view-up",
         [&view, anatomical](const std::string& s) {
           if (anatomical && is_anatomical_view(s)) {
             anatomical->up = s;
             return;
           }
           try {
             view.view_up = parse_direction(s);
           } catch (const Error& e) {
             throw CLI::ValidationError("--view-up", e.what());
           }
         },
         std::string("The picture's up direction: +x -x +y -y +z -z or X,Y,Z (e.g. -z for a scan "
                     "stored head down)") +
             (anatomical ? "; anatomical volumes also superior, inferior, anterior, ..." : ""))
      ->group("Camera");
  cmd.add_option("--azimuth", view.azimuth_deg,
                 "Then turn the camera this many degrees about the view up")
      ->check(CLI::Range(-360.0, 360.0))
      ->group("Camera");
  cmd.add_option("--elevation", view.elevation_deg,
                 "Then raise the camera this many degrees (-180..180: over the top and beyond)")
      ->check(CLI::Range(-180.0, 180.0))
      ->group("Camera");
  cmd.add_option("--roll", view.roll_deg,
                 "Last, turn the picture this many degrees anticlockwise")
      ->check(CLI::Range(-360.0, 360.0))
      ->group("Camera");
  cmd.add_option("--zoom", view.zoom,
                 "Magnification after fitting the surface into the view (default 1)")
      ->check(CLI::Range(0.05, 50.0))
      ->group("Camera");
  cmd.add_flag("--ortho", view.ortho, "Parallel projection instead of perspective")
      ->group("Camera");
}

ViewSpec resolve_view(const ViewSpec& view, const AnatomicalCli& anatomical,
                      const std::string& world_space, const std::string& input) {
  ViewSpec v = view;
  const auto frame = anatomical_frame(world_space);
  for (const std::string* name : {&anatomical.view, &anatomical.up})
    if (!name->empty() && !frame)
      throw Error(input,
                  std::string(name == &anatomical.view ? "--view " : "--view-up ") + *name +
                      " needs a volume whose world axes are anatomical (NIfTI: RAS, MetaImage: "
                      "LPS, NRRD with a space field, or a mesh isocurv made from one); use " +
                      (name == &anatomical.view ? "iso, +x, -x, +y, -y, +z or -z"
                                                : "+x, -x, +y, -y, +z, -z or X,Y,Z"));
  if (frame) {
  if (!anatomical.view.empty())
    v.axes = anatomical_axes(anatomical.view, *frame);
  else if (!anatomical.view_given)
    v.axes = anatomical_axes("iso", *frame);  // the face, superior up
  if (!anatomical.up.empty()) {
    // The anatomical direction as a world vector: the first axis of the view that looks from it.
    v.view_up = anatomical_axes(anatomical.up, *frame).first;
  }
  }
  std::array<double, 3> toward, up;
  view_axes(v, toward, up);  // an up along the view: the error now, before any work
  return v;
}

std::optional<AnatomicalFrame> anatomical_frame(const std::string& world_space) {
  return anatomical_frame_named(world_space);
}

namespace {
/// An array `features` computes (features::feature_name).
bool is_feature_array(const std::string& name) {
  for (features::Feature f : features::parse_features("all"))
    if (name == features::feature_name(f)) return true;
  return false;
}
}  // namespace

viz::RenderOptions render_options_for(const RenderCli& r, const std::string& input,
                                      const SurfaceContext& context, const std::string& estimator,
                                      const curvature::CurvatureField* field) {
  viz::RenderOptions o = r.opts;
  if (o.length_unit.empty()) o.length_unit = context.length_unit;
  o.view = resolve_view(o.view, r.anatomical, context.world_space, input);
  if (field) {
    try {
      o.color = viz::resolve_quantity(*field, o.color);
    } catch (const Error& e) {
      throw Error(input, e.what());
    }
  }
  if (!r.camera_file.empty()) o.camera = viz::load_camera(r.camera_file);
  // A features mesh of one radius: its arrays have no _r suffix, the title gets the file's radius.
  std::string quantity = o.color;
  const viz::QuantityName n = viz::split_quantity_name(o.color);
  if (!context.feature_radius.empty() && n.radius.empty() && n.scale.empty() && is_feature_array(n.base))
    quantity += "_r" + context.feature_radius;
  o.title = r.title.empty() ? picture_title(input, quantity, context.isovalue, estimator) : r.title;
  return o;
}

}  // namespace isocurv::app
