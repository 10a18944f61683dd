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

std::string estimator_title(const curvature::EstimatorReport& report) {
  std::string t = report.estimator;
  for (std::size_t i = 0; i < report.parameters.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%s %g", i == 0 ? ", " : " ", report.parameters[i].first.c_str(),
                  report.parameters[i].second);
    t += buf;
  }
  return t;
}

std::string estimator_title(const CommonOptions& o) {
  const std::string name = o.estimator.empty() ? "rusinkiewicz" : o.estimator;
  return name == "volume" ? name + ", scale " + o.scale : name;
}

}  // namespace isocurv::app
