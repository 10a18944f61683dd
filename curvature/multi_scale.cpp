#include "curvature/multi_scale.h"

#include <algorithm>

#include "core/error.h"

namespace isocurv::curvature {

const std::vector<std::string>& per_scale_arrays() {
  static const std::vector<std::string> names = {"k1",         "k2",         "H",         "K",
                                                 "ShapeIndex", "Curvedness", "Unreliable"};
  return names;
}

std::string scale_array_name(const std::string& array, const std::string& scale_name) {
  return array + "_s" + scale_name;
}

void append_scale_arrays(const CurvatureField& at_scale, const std::string& scale_name,
                         CurvatureField& out) {
  if (at_scale.size() != out.size())
    throw Error("curvature: the field at scale " + scale_name + " has " +
                std::to_string(at_scale.size()) + " vertices, not " + std::to_string(out.size()));
  const std::vector<const std::vector<float>*> scalars = {
      &at_scale.k1, &at_scale.k2,          &at_scale.H,
      &at_scale.K,  &at_scale.shape_index, &at_scale.curvedness};
  const std::vector<std::string>& names = per_scale_arrays();
  auto add = [&](const std::string& array, std::vector<float> values) {
    const std::string name = scale_array_name(array, scale_name);
    if (std::any_of(out.extra.begin(), out.extra.end(),
                    [&](const CurvatureField::Named& n) { return n.name == name; }))
      throw Error("curvature: scale " + scale_name + " given twice (array " + name + ")");
    out.extra.push_back({name, std::move(values)});
  };
  for (std::size_t i = 0; i < scalars.size(); ++i) add(names[i], *scalars[i]);
  if (std::any_of(at_scale.unreliable.begin(), at_scale.unreliable.end(),
                  [](std::uint8_t u) { return u != 0; }))
    add(names.back(), std::vector<float>(at_scale.unreliable.begin(), at_scale.unreliable.end()));
}

}  // namespace isocurv::curvature
