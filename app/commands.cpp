#include "app/commands.h"

namespace isocurv::app {

void register_commands(CLI::App& app) {
  register_info(app);
  register_extract(app);
  register_curvature(app);
  register_features(app);
  register_run(app);
  register_render(app);
  register_lines(app);
  register_deform(app);
  register_screen(app);
  register_view(app);
  register_check(app);
  register_compare(app);
  register_devices(app);
}

}  // namespace isocurv::app
