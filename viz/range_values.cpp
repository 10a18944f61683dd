#include "viz/range_values.h"

#include <algorithm>

#include "core/mesh_measures.h"
#include "curvature/field_stats.h"
#include "viz/quantity.h"

namespace isocurv::viz {

std::vector<float> range_values(const Mesh& mesh, const curvature::CurvatureField& field,
                                const std::string& quantity) {
  std::vector<float> values = quantity_values(field, quantity);
  const std::vector<std::uint8_t>* unmeasured =
      field.unreliable.size() == values.size() && quantity_kind(quantity) != QuantityKind::flag
          ? &field.unreliable
          : nullptr;
  const std::vector<std::uint8_t> counted =
      curvature::counted_vertices(field, mean_edge_length(mesh));
  const bool use_counted = counted.size() == values.size() &&
                           std::any_of(counted.begin(), counted.end(), [](std::uint8_t c) { return c; });
  const bool use_boundary = field.boundary.size() == values.size();
  std::vector<float> inner;
  inner.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    if ((!use_counted || counted[i]) && !(use_boundary && field.boundary[i]) &&
        !(unmeasured && (*unmeasured)[i]))
      inner.push_back(values[i]);
  return inner.empty() ? values : inner;
}

}  // namespace isocurv::viz
