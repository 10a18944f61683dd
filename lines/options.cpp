#include "lines/options.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace isocurv::lines {

Thresholds resolve_thresholds(const curvature::CurvatureField &field,
                              const Options &options) {
  auto check = [](double x, const char *what) {
    if (!std::isfinite(x) || x < 0)
      throw Error(std::string("lines: ") + what + " must be finite and >= 0");
  };
  check(options.suggestive_threshold, "the suggestive-contour threshold");
  check(options.ridge_threshold, "the ridge threshold");
  if (!(options.suggestive_angle_deg >= 0 && options.suggestive_angle_deg < 90))
    throw Error(
        "lines: the suggestive-contour angle must lie in [0, 90) degrees");
  if (options.smoothing_steps < 0 || options.smoothing_steps > 100)
    throw Error("lines: the smoothing steps must lie in 0..100");
  std::vector<float> k;
  k.reserve(field.k1.size());
  for (std::size_t i = 0; i < field.k1.size() && i < field.k2.size(); ++i) {
    const float m = std::max(std::fabs(field.k1[i]), std::fabs(field.k2[i]));
    if (std::isfinite(m))
      k.push_back(m);
  }
  Thresholds t;
  if (!k.empty()) {
    auto mid = k.begin() + k.size() / 2;
    std::nth_element(k.begin(), mid, k.end());
    t.typical_curvature = *mid;
  }
  const double m = t.typical_curvature;
  t.suggestive = options.suggestive_threshold * m * m;
  t.ridge = options.ridge_threshold * m;
  t.cos_angle =
      std::cos(options.suggestive_angle_deg * 3.14159265358979323846 / 180);
  return t;
}

} // namespace isocurv::lines
