// Feature names and the --features list.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "features/features.h"

namespace isocurv::features {

namespace {
constexpr Feature kAll[] = {Feature::LBE,  Feature::NSV,  Feature::Vr,
                            Feature::H_ii, Feature::K_ii, Feature::SI_ii};
}

const char *feature_name(Feature f) {
  switch (f) {
  case Feature::LBE:
    return "LBE";
  case Feature::NSV:
    return "NSV";
  case Feature::Vr:
    return "Vr";
  case Feature::H_ii:
    return "H_ii";
  case Feature::K_ii:
    return "K_ii";
  case Feature::SI_ii:
    return "SI_ii";
  }
  return "?";
}

void parse_radii(const std::string &list, double diagonal, Options &o) {
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    start = comma + 1;
    const bool percent = !item.empty() && item.back() == '%';
    const std::string number = percent ? item.substr(0, item.size() - 1) : item;
    std::size_t used = 0;
    double r = 0;
    try {
      r = std::stod(number, &used);
    } catch (const std::exception &) {
      used = 0;
    }
    if (number.empty() || used != number.size() || !(r > 0) || !std::isfinite(r))
      throw Error("'" + item +
                  "' is not a positive number (world units, or N% of the bounding-box diagonal)");
    o.radii.push_back(percent ? r / 100 * diagonal : r);
    o.radius_names.push_back(item);
  }
}

std::vector<Feature> parse_features(const std::string &list) {
  if (list == "all")
    return {std::begin(kAll), std::end(kAll)};
  std::vector<Feature> out;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    bool found = false;
    for (Feature f : kAll)
      if (item == feature_name(f)) {
        found = true;
        bool seen = false;
        for (Feature g : out)
          seen = seen || g == f;
        if (!seen)
          out.push_back(f);
      }
    if (!found)
      throw Error("unknown feature '" + item +
                  "' (expected LBE, NSV, Vr, H_ii, K_ii, SI_ii or all)");
  }
  if (out.empty())
    throw Error(
        "no features named (expected LBE, NSV, Vr, H_ii, K_ii, SI_ii or all)");
  return out;
}

} // namespace isocurv::features
