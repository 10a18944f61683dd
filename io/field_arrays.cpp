#include "io/field_arrays.h"

#include "core/error.h"

namespace isocurv::io {

void check_field_sizes(const curvature::CurvatureField& field, std::size_t vertex_count,
                       const std::string& path) {
  for_each_array(field, [&](const char* name, const auto& values) {
    if (!values.empty() && values.size() != vertex_count)
      throw Error(path, std::string("curvature array '") + name + "' has " +
                            std::to_string(values.size()) + " values for " +
                            std::to_string(vertex_count) + " vertices");
  });
}

bool is_curvature_array(const std::string& name) {
  static const curvature::CurvatureField empty;
  bool found = false;
  for_each_array(empty, [&](const char* n, const auto&) { found = found || name == n; });
  return found;
}

bool field_is_empty(const curvature::CurvatureField& field) {
  bool empty = true;
  for_each_array(field, [&](const char*, const auto& values) { empty = empty && values.empty(); });
  return empty;
}

curvature::CurvatureField select_vertices(const curvature::CurvatureField& field,
                                          const std::vector<std::uint32_t>& index) {
  curvature::CurvatureField out = field;
  auto pick = [&](auto& v) {
    if (v.empty()) return;
    const auto src = v;
    v.resize(index.size());
    for (std::size_t i = 0; i < index.size(); ++i) v[i] = src[index[i]];
  };
  for_each_array(out, [&](const char*, auto& v) { pick(v); });
  pick(out.surface_points);
  return out;
}

}  // namespace isocurv::io
