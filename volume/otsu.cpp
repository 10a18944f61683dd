#include "volume/otsu.h"

#include <cstddef>

namespace isocurv::volume {

double otsu_threshold(const std::vector<std::uint64_t>& histogram, double min, double max) {
  const std::size_t n = histogram.size();
  if (n < 2 || !(max > min)) return min;
  double total = 0, total_sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    total += double(histogram[i]);
    total_sum += double(i) * double(histogram[i]);
  }
  if (total <= 0) return min;

  // Boundary k separates bins [0, k) from [k, n). Between-class variance (up to a constant factor):
  // w0 * w1 * (mu0 - mu1)^2.
  double w0 = 0, sum0 = 0, best = -1;
  std::size_t first_best = 1, last_best = 1;
  for (std::size_t k = 1; k < n; ++k) {
    w0 += double(histogram[k - 1]);
    sum0 += double(k - 1) * double(histogram[k - 1]);
    const double w1 = total - w0;
    if (w0 <= 0 || w1 <= 0) continue;
    const double d = sum0 / w0 - (total_sum - sum0) / w1;
    const double var = w0 * w1 * d * d;
    // Relative tolerance so that exactly tied boundaries (empty bins in between) form one run.
    if (var > best * (1 + 1e-12)) {
      best = var;
      first_best = last_best = k;
    } else if (var >= best * (1 - 1e-12)) {
      last_best = k;
    }
  }
  if (best < 0) return min;  // a single occupied bin
  const double k = 0.5 * double(first_best + last_best);
  return min + k * (max - min) / double(n);
}

}  // namespace isocurv::volume
