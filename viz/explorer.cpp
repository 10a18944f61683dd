// run_explorer: checks the setup and runs one detail::Explorer (viz/detail/explorer.h, whose
// parts live in viz/detail/explorer_*.cpp by concern).
#include "viz/explorer.h"

#include <cstdlib>
#include <string>

#include "core/error.h"
#include "viz/detail/explorer.h"
#include "viz/headless_display.h"
#include "viz/quantity.h"

namespace isocurv::viz {

void run_explorer(const ExplorerSetup& setup) {
  if (!setup.surface) throw Error("explorer: no surface callback given");
  if (setup.has_isovalue && !(setup.min_value < setup.max_value))
    throw Error("explorer: empty isovalue range [" + std::to_string(setup.min_value) + ", " +
                std::to_string(setup.max_value) + "]");
  if (setup.has_isovalue && (setup.isovalue < setup.min_value || setup.isovalue > setup.max_value))
    throw Error("explorer: isovalue " + std::to_string(setup.isovalue) + " outside the value range [" +
                std::to_string(setup.min_value) + ", " + std::to_string(setup.max_value) + "]");
  if (setup.view.width < 64 || setup.view.height < 64) throw Error("explorer: window too small");
  canonical_quantity(setup.view.color);
  const char* display = std::getenv("DISPLAY");
  if (setup.script.empty() && !(display && *display))
    throw Error("no X display (DISPLAY is unset): the interactive explorer needs one; render PNGs headless instead");
  ensure_display(setup.script.empty() ? DisplayUse::interactive : DisplayUse::offscreen);
  detail::Explorer explorer(setup);
  explorer.run();
}

}  // namespace isocurv::viz
