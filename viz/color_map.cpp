#include "viz/color_map.h"

#include <vtkColorTransferFunction.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"
#include "viz/quantity.h"

namespace isocurv::viz {
namespace {

using Rgb = std::array<double, 3>;

/// ColorBrewer RdBu (9 classes), blue end first: colour-blind safe, light neutral in the middle.
const std::vector<Rgb> kDiverging = {
    {0x21 / 255., 0x66 / 255., 0xac / 255.}, {0x43 / 255., 0x93 / 255., 0xc3 / 255.},
    {0x92 / 255., 0xc5 / 255., 0xde / 255.}, {0xd1 / 255., 0xe5 / 255., 0xf0 / 255.},
    {0xf7 / 255., 0xf7 / 255., 0xf7 / 255.}, {0xfd / 255., 0xdb / 255., 0xc7 / 255.},
    {0xf4 / 255., 0xa5 / 255., 0x82 / 255.}, {0xd6 / 255., 0x60 / 255., 0x4d / 255.},
    {0xb2 / 255., 0x18 / 255., 0x2b / 255.}};
/// matplotlib's viridis at t = 0, 1/8, ..., 1 (entries 0, 32, ..., 224, 255 of its table).
const std::vector<Rgb> kViridis = {
    {0.267004, 0.004874, 0.329415}, {0.282623, 0.140926, 0.457517}, {0.229739, 0.322361, 0.545706},
    {0.172719, 0.448791, 0.557885}, {0.127568, 0.566949, 0.550556}, {0.134692, 0.658636, 0.517649},
    {0.369214, 0.788888, 0.382914}, {0.678489, 0.863742, 0.189503}, {0.993248, 0.906157, 0.143936}};
const std::vector<Rgb> kGrey = {{0, 0, 0}, {1, 1, 1}};
/// The papers' map: blue negative, green zero, red positive.
const std::vector<Rgb> kBlueGreenRed = {{0.15, 0.25, 0.90}, {0.20, 0.78, 0.25}, {0.90, 0.15, 0.10}};

const std::vector<Rgb>& stops(const std::string& cmap) {
  if (cmap == "diverging") return kDiverging;
  if (cmap == "viridis") return kViridis;
  if (cmap == "grey") return kGrey;
  if (cmap == "bgr") return kBlueGreenRed;
  throw Error("unknown colour map '" + cmap + "' (choose auto, diverging, viridis, grey or bgr)");
}

/// The q-th percentile (q in [0, 100]) of `v` (reordered), nearest rank.
double percentile(std::vector<double>& v, double q) {
  if (v.empty()) return 0;
  q = std::clamp(q, 0.0, 100.0);
  const auto k =
      static_cast<std::size_t>(std::llround(q / 100.0 * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// Vertex i's colour `rgb` (in [0, 1]) as bytes into out[3 i ..], times its AO when `ao` is given
/// (clamped to [0, 1]; a non-finite AO counts as 1).
void store_shaded(unsigned char* out, std::size_t i, const double* rgb, const std::vector<float>* ao) {
  double shade = 1;
  if (ao) shade = std::isfinite((*ao)[i]) ? std::clamp(double((*ao)[i]), 0.0, 1.0) : 1.0;
  for (int c = 0; c < 3; ++c)
    out[3 * i + static_cast<std::size_t>(c)] = static_cast<unsigned char>(std::lround(255 * rgb[c] * shade));
}

constexpr int kTableSize = 1024;
constexpr double kMaxClampPercentile = 49;

}  // namespace

const std::vector<std::string>& color_map_names() {
  static const std::vector<std::string> names = {"auto", "diverging", "viridis", "grey", "bgr"};
  return names;
}

std::string resolve_color_map(const std::string& cmap, const std::string& quantity) {
  if (cmap != "auto") {
    stops(cmap);  // throws for an unknown name
    return cmap;
  }
  if (is_signed_quantity(quantity)) return "diverging";
  return quantity_kind(quantity) == QuantityKind::occlusion ? "grey" : "viridis";
}

bool is_centred_map(const std::string& cmap) { return cmap == "diverging" || cmap == "bgr"; }

ColorRange color_range(const std::vector<float>& values, const std::string& name,
                       double clamp_percentile, const std::optional<ColorRange>& fixed) {
  const QuantityKind kind = quantity_kind(name);
  if (fixed) {
    if (!(fixed->lo < fixed->hi) || !std::isfinite(fixed->lo) || !std::isfinite(fixed->hi))
      throw Error("colour range " + std::to_string(fixed->lo) + " .. " + std::to_string(fixed->hi) +
                  " is empty: MIN must be below MAX");
    return *fixed;
  }
  if (kind == QuantityKind::shape_index) return {-1, 1};
  if (kind == QuantityKind::occlusion || kind == QuantityKind::flag) return {0, 1};
  const double c = std::clamp(clamp_percentile, 0.0, kMaxClampPercentile);
  std::vector<double> finite;
  finite.reserve(values.size());
  for (float v : values)
    if (std::isfinite(v)) finite.push_back(v);
  ColorRange range{0, 0};
  if (kind == QuantityKind::label && !finite.empty()) {
    const auto [lo, hi] = std::minmax_element(finite.begin(), finite.end());
    range = {*lo, *hi};
  } else if (kind == QuantityKind::curvature) {
    const double lo = percentile(finite, c), hi = percentile(finite, 100.0 - c);
    if (lo < 0 && hi > 0) {
      for (double& v : finite) v = std::fabs(v);
      const double r = percentile(finite, 100.0 - c);
      range = {-r, r};
    } else if (hi > 0) {
      range = {0, hi};
    } else {
      range = {lo, 0};
    }
  } else if (kind == QuantityKind::magnitude) {
    range = {0, percentile(finite, 100.0 - c)};
  } else {
    range = {percentile(finite, c), percentile(finite, 100.0 - c)};
  }
  if (!(range.hi > range.lo)) {  // all equal (or nothing finite): a small range around them
    if (kind == QuantityKind::other || kind == QuantityKind::label) {
      const double v = range.lo, half = std::max(1e-6, 1e-3 * std::fabs(v));
      return {v - half, v + half};
    }
    const double half = std::max({1e-6, std::fabs(range.lo), std::fabs(range.hi)});
    range = kind == QuantityKind::curvature ? ColorRange{-half, half} : ColorRange{0, half};
  }
  return range;
}

vtkSmartPointer<vtkColorTransferFunction> make_color_map(const ColorRange& range,
                                                         const std::string& cmap) {
  const std::vector<Rgb>& rgb = stops(cmap);
  double a = range.lo, b = range.hi;  // the values of the first and the last stop
  if (is_centred_map(cmap) && a <= 0 && b >= 0) {
    const double m = std::max(-a, b);
    a = -m, b = m;
  }
  auto map = vtkSmartPointer<vtkColorTransferFunction>::New();
  map->SetColorSpaceToRGB();
  const std::size_t n = rgb.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double t = double(i) / double(n - 1);
    // the centre stop exactly at (a + b) / 2: zero for a centred map over a range with zero
    const double v = (2 * i + 1 == n) ? 0.5 * (a + b) : a + t * (b - a);
    map->AddRGBPoint(v, rgb[i][0], rgb[i][1], rgb[i][2]);
  }
  map->ClampingOn();
  return map;
}

std::array<double, 3> no_data_color(const std::string& cmap) {
  if (cmap == "diverging") return {1.0, 0.85, 0.0};
  if (cmap == "bgr") return {0.9, 0.0, 0.9};
  return {0.9, 0.0, 0.0};
}

vtkSmartPointer<vtkUnsignedCharArray> vertex_colors(const std::vector<float>& values,
                                                    const ColorRange& range,
                                                    vtkColorTransferFunction* map,
                                                    const std::vector<float>* ao,
                                                    const std::vector<std::uint8_t>* no_data,
                                                    const std::array<double, 3>& no_data_rgb) {
  if (no_data && no_data->size() != values.size()) no_data = nullptr;
  std::vector<double> table(3 * kTableSize);
  map->GetTable(range.lo, range.hi, kTableSize, table.data());
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  unsigned char* out = colors->GetPointer(0);
  const double scale = (kTableSize - 1) / (range.hi - range.lo);
  for (std::size_t i = 0; i < values.size(); ++i) {
    double rgb[3] = {no_data_rgb[0], no_data_rgb[1], no_data_rgb[2]};
    if (std::isfinite(values[i]) && !(no_data && (*no_data)[i])) {
      const double t = std::clamp((values[i] - range.lo) * scale, 0.0, double(kTableSize - 1));
      const auto k = static_cast<std::size_t>(std::lround(t));
      std::copy(table.begin() + 3 * k, table.begin() + 3 * k + 3, rgb);
    }
    store_shaded(out, i, rgb, ao);
  }
  return colors;
}

const std::array<std::array<double, 3>, kCategoricalColors>& categorical_palette() {
  // Sasha Trubetskoy's 20 distinct colours, in his order (neighbours far apart), less his red
  // and maroon: the "no data" colour beside a label map is red.
  static const std::array<std::array<double, 3>, kCategoricalColors> palette = [] {
    const unsigned hex[kCategoricalColors] = {0x3cb44b, 0xffe119, 0x4363d8, 0xf58231, 0x911eb4, 0x42d4f4,
                                              0xf032e6, 0xbfef45, 0xfabed4, 0x469990, 0xdcbeff, 0x9a6324,
                                              0xfffac8, 0xaaffc3, 0x808000, 0xffd8b1, 0x000075, 0xa9a9a9};
    std::array<std::array<double, 3>, kCategoricalColors> p{};
    for (std::size_t i = 0; i < kCategoricalColors; ++i)
      p[i] = {((hex[i] >> 16) & 255) / 255.0, ((hex[i] >> 8) & 255) / 255.0, (hex[i] & 255) / 255.0};
    return p;
  }();
  return palette;
}

std::vector<double> categories_of(const std::vector<float>& values) {
  std::vector<double> out;
  for (float v : values)
    if (std::isfinite(v)) out.push_back(v);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::array<double, 3> categorical_color(std::size_t index) {
  return categorical_palette()[index % kCategoricalColors];
}

vtkSmartPointer<vtkUnsignedCharArray> categorical_vertex_colors(
    const std::vector<float>& values, const std::vector<double>& categories,
    const std::vector<float>* ao, const std::vector<std::uint8_t>* no_data,
    const std::array<double, 3>& no_data_rgb) {
  if (no_data && no_data->size() != values.size()) no_data = nullptr;
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  unsigned char* out = colors->GetPointer(0);
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::array<double, 3> rgb = no_data_rgb;
    if (std::isfinite(values[i]) && !(no_data && (*no_data)[i])) {
      const auto it = std::lower_bound(categories.begin(), categories.end(), double(values[i]));
      if (it != categories.end() && *it == double(values[i]))
        rgb = categorical_color(static_cast<std::size_t>(it - categories.begin()));
    }
    store_shaded(out, i, rgb.data(), ao);
  }
  return colors;
}

}  // namespace isocurv::viz
