#include "app/picture_title.h"

#include <cstdio>
#include <filesystem>

#include "viz/quantity.h"

namespace isocurv::app {

std::string picture_title(const std::string& input, const std::string& quantity,
                          std::optional<float> isovalue, const std::string& estimator) {
  constexpr const char* kSeparator = "  |  ";
  std::string title = std::filesystem::path(input).filename().string();
  title += kSeparator + viz::quantity_description(quantity);
  if (isovalue) {
    char text[32];
    std::snprintf(text, sizeof text, "iso %g", double(*isovalue));
    title += kSeparator + std::string(text);
  }
  if (!estimator.empty()) title += kSeparator + estimator;
  return title;
}

}  // namespace isocurv::app
