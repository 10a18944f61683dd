#include "lines/options.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/error.h"

namespace isocurv::lines {
namespace {

constexpr std::uint32_t kNotFinite = 0xffffffffu;  // a NaN's bits: no finite value has them

// max(|k1|, |k2|) of vertex i, as its float's bits: for non-negative floats these order like the
// values. kNotFinite where that maximum is not finite.
std::uint32_t magnitude_bits(const curvature::CurvatureField& field, std::size_t i) {
  const float m = std::max(std::fabs(field.k1[i]), std::fabs(field.k2[i]));
  std::uint32_t bits;
  std::memcpy(&bits, &m, sizeof bits);
  return std::isfinite(m) ? bits : kNotFinite;
}

// The exact median (the element nth_element would put in the middle) of the vertices' finite
// max(|k1|, |k2|), 0 when there is none: a radix select on the floats' bits, one pass over the
// vertices for the high 16 bits and one for the low 16 bits inside the bucket holding the median.
double median_principal_magnitude(const curvature::CurvatureField& field) {
  const std::size_t n = std::min(field.k1.size(), field.k2.size());
  std::vector<std::uint32_t> count(1 << 16, 0);
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t b = magnitude_bits(field, i);
    if (b != kNotFinite) ++count[b >> 16], ++finite;
  }
  if (finite == 0) return 0;
  std::size_t rank = finite / 2;  // the median's rank among the finite values, from 0
  auto bucket_of_rank = [&] {
    std::uint32_t b = 0;
    while (rank >= count[b]) rank -= count[b++];
    return b;
  };
  const std::uint32_t high = bucket_of_rank();
  std::fill(count.begin(), count.end(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t b = magnitude_bits(field, i);
    if (b != kNotFinite && b >> 16 == high) ++count[b & 0xffff];
  }
  const std::uint32_t bits = high << 16 | bucket_of_rank();
  float m;
  std::memcpy(&m, &bits, sizeof m);
  return m;
}

}  // namespace

Thresholds resolve_thresholds(const curvature::CurvatureField& field, const Options& options) {
  auto check = [](double x, const char* what) {
    if (!std::isfinite(x) || x < 0)
      throw Error(std::string("lines: ") + what + " must be finite and >= 0");
  };
  check(options.suggestive_threshold, "the suggestive-contour threshold");
  check(options.ridge_threshold, "the ridge threshold");
  if (!(options.suggestive_angle_deg >= 0 && options.suggestive_angle_deg < 90))
    throw Error("lines: the suggestive-contour angle must lie in [0, 90) degrees");
  if (options.smoothing_steps < 0 || options.smoothing_steps > 100)
    throw Error("lines: the smoothing steps must lie in 0..100");
  Thresholds t;
  t.typical_curvature = median_principal_magnitude(field);
  const double m = t.typical_curvature;
  t.suggestive = options.suggestive_threshold * m * m;
  t.ridge = options.ridge_threshold * m;
  t.cos_angle = std::cos(options.suggestive_angle_deg * 3.14159265358979323846 / 180);
  return t;
}

}  // namespace isocurv::lines
