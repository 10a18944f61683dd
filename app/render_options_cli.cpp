#include "app/render_options_cli.h"

#include <cstdio>

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
}

}  // namespace isocurv::app
