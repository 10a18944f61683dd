#include "app/render_options_cli.h"

#include <cstdio>

#include "core/error.h"

namespace isocurv::app {

void add_render_options(CLI::App& cmd, viz::RenderOptions& opts) {
  cmd.add_option("--color", opts.color, "Quantity to colour by (blue negative, green zero, red positive)")
      ->check(CLI::IsMember({"H", "K", "k1", "k2", "ShapeIndex", "Curvedness", "AO"}))->capture_default_str()->group("Rendering");
  cmd.add_flag("--ao", opts.ao, "Shade with curvature-based ambient occlusion")->group("Rendering");
  cmd.add_flag("--dirs", opts.dirs, "Draw principal directions (dir1 white, dir2 black) on a subsample of vertices")->group("Rendering");
  cmd.add_option_function<std::string>("--size", [&opts](const std::string& s) {
    int w = 0, h = 0;
    char x = 0;
    if (std::sscanf(s.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 16 || h < 16 || w > 8192 || h > 8192)
      throw CLI::ValidationError("--size", "expected WIDTHxHEIGHT, each 16..8192, e.g. 1024x768");
    opts.width = w;
    opts.height = h;
  }, "Image size WIDTHxHEIGHT (default 1024x768)")->group("Rendering");
  add_camera_options(cmd, opts.view);
}

void add_camera_options(CLI::App& cmd, ViewSpec& view) {
  cmd.add_option_function<std::string>("--view", [&view](const std::string& s) {
    try {
      view.view = parse_named_view(s);
    } catch (const Error& e) {
      throw CLI::ValidationError("--view", e.what());
    }
  }, "Viewpoint: iso (three-quarter view from above, the default), or +x -x +y -y +z -z (the camera on that side of the centre, looking at it)")->group("Camera");
  cmd.add_option("--azimuth", view.azimuth_deg, "Then turn the camera this many degrees about the view up")
      ->check(CLI::Range(-360.0, 360.0))->group("Camera");
  cmd.add_option("--elevation", view.elevation_deg, "Then raise the camera this many degrees")
      ->check(CLI::Range(-90.0, 90.0))->group("Camera");
  cmd.add_option("--zoom", view.zoom, "Magnification after fitting the surface into the view (default 1)")
      ->check(CLI::Range(0.05, 50.0))->group("Camera");
  cmd.add_flag("--ortho", view.ortho, "Parallel projection instead of perspective")->group("Camera");
}

}  // namespace isocurv::app
