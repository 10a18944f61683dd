// Screenshots: 's' (the next free <prefix>-NNN.png) and scripted ones.
#include "viz/detail/explorer.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "core/error.h"
#include "viz/screenshot.h"

namespace isocurv::viz::detail {

std::string Explorer::next_screenshot_name() {
  for (;;) {
    char suffix[24];
    std::snprintf(suffix, sizeof suffix, "-%03d.png", ++screenshots_);
    const std::string name = setup_.screenshot_prefix + suffix;
    if (!std::filesystem::exists(name)) return name;
  }
}

void Explorer::screenshot(const std::string& path) {
  try {
    save_png(window_, path);
    message_ = "saved " + path;
    std::cout << "saved screenshot: " << path << std::endl;
  } catch (const Error& e) {
    message_ = e.what();
    std::cerr << e.what() << std::endl;
  }
}

}  // namespace isocurv::viz::detail
