#include "app/commands.h"

namespace isocurv::app {

void register_commands(CLI::App& app) {
  register_info(app);
  register_devices(app);
}

}  // namespace isocurv::app
