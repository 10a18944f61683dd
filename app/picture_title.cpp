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
  // A label map's colours are its labels: the curvature's estimator and scale say nothing there.
  if (!estimator.empty() && viz::quantity_kind(quantity) != viz::QuantityKind::label)
    title += kSeparator + estimator;
  return title;
}

std::string estimator_title(const curvature::EstimatorReport& report) {
  // Only the parameter that changes what the picture shows (the volume estimator's scale): with
  // a per-vertex scale its range (5th to 95th percentile), not the pilot.
  std::string t = report.estimator;
  std::optional<double> scale, p5, p95;
  for (const auto& [name, value] : report.parameters) {
    if (name == "scale") scale = value;
    if (name == "scale_p5") p5 = value;
    if (name == "scale_p95") p95 = value;
  }
  char buf[96];
  if (p5 && p95 && *p5 != *p95)
    std::snprintf(buf, sizeof buf, ", scale %.3g-%.3g per vertex", *p5, *p95);
  else if (p5 || scale)
    std::snprintf(buf, sizeof buf, ", scale %.3g", p5 ? *p5 : *scale);
  else
    return t;
  return t + buf;
}

std::string estimator_title(const CommonOptions& o) {
  const std::string name = curvature::estimator_name(default_estimator(o, true));
  return name == "volume" ? name + ", scale " + o.scale : name;
}

std::string with_ao(const std::string& estimator, const CommonOptions& o) {
  if (o.ao.empty() || o.ao == "griffin") return estimator;
  return (estimator.empty() ? "" : estimator + ", ") + "AO " + o.ao;
}

}  // namespace isocurv::app
