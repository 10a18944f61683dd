#include "viz/color_map.h"

#include <algorithm>
#include <cmath>

#include <vtkColorTransferFunction.h>
#include <vtkUnsignedCharArray.h>

#include "viz/quantity.h"

namespace isocurv::viz {
namespace {

/// The q-th percentile (q in [0, 100]) of `v` (reordered), nearest rank.
double percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  q = std::clamp(q, 0.0, 100.0);
  const auto k = static_cast<std::size_t>(std::llround(q / 100.0 * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

constexpr int kTableSize = 256;

}  // namespace

ColorRange color_range(const std::vector<float>& values, const std::string& name, double clamp_percentile) {
  const std::string q = canonical_quantity(name);
  if (q == "ShapeIndex") return {-1, 1};
  const bool symmetric = is_signed_quantity(q);
  std::vector<double> finite;
  finite.reserve(values.size());
  for (float v : values)
    if (std::isfinite(v)) finite.push_back(symmetric ? std::fabs(v) : v);
  const double c = std::clamp(clamp_percentile, 0.0, 49.0);
  ColorRange range;
  if (symmetric) {
    const double r = percentile(finite, 100.0 - c);
    range = {-r, r};
  } else {
    range.hi = percentile(finite, 100.0 - c);
    range.lo = percentile(finite, c);
  }
  if (!(range.hi > range.lo)) {  // all equal (or nothing finite): a small range around the value
    const double mid = 0.5 * (range.lo + range.hi);
    const double half = std::max(1e-6, std::fabs(mid) * 1e-3);
    range = symmetric ? ColorRange{-std::max(half, std::fabs(mid)), std::max(half, std::fabs(mid))}
                      : ColorRange{mid - half, mid + half};
  }
  return range;
}

vtkSmartPointer<vtkColorTransferFunction> make_color_map(const ColorRange& range) {
  auto map = vtkSmartPointer<vtkColorTransferFunction>::New();
  map->SetColorSpaceToRGB();
  const double mid = 0.5 * (range.lo + range.hi);
  map->AddRGBPoint(range.lo, 0.15, 0.25, 0.90);  // blue: negative
  map->AddRGBPoint(mid, 0.20, 0.78, 0.25);       // green: zero for signed quantities
  map->AddRGBPoint(range.hi, 0.90, 0.15, 0.10);  // red: positive
  map->ClampingOn();
  return map;
}

vtkSmartPointer<vtkUnsignedCharArray> vertex_colors(const std::vector<float>& values, const ColorRange& range,
                                                    vtkColorTransferFunction* map, const std::vector<float>* ao) {
  double table[3 * kTableSize];
  map->GetTable(range.lo, range.hi, kTableSize, table);
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  unsigned char* out = colors->GetPointer(0);
  const double scale = (kTableSize - 1) / (range.hi - range.lo);
  for (std::size_t i = 0; i < values.size(); ++i) {
    double rgb[3] = {0.5, 0.5, 0.5};
    if (std::isfinite(values[i])) {
      const double t = std::clamp((values[i] - range.lo) * scale, 0.0, double(kTableSize - 1));
      const int k = static_cast<int>(std::lround(t));
      std::copy(table + 3 * k, table + 3 * k + 3, rgb);
    }
    double shade = 1;
    if (ao) shade = std::isfinite((*ao)[i]) ? std::clamp(double((*ao)[i]), 0.0, 1.0) : 1.0;
    for (int c = 0; c < 3; ++c)
      out[3 * i + static_cast<std::size_t>(c)] = static_cast<unsigned char>(std::lround(255 * rgb[c] * shade));
  }
  return colors;
}

}  // namespace isocurv::viz
