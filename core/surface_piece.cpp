#include "core/surface_piece.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace isocurv {
namespace {

std::uint32_t bits_of(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

}  // namespace

std::uint64_t total_count(const SurfacePiece* piece, std::uint64_t n) {
  if (!piece) return n;
  return std::uint64_t(piece->sum({std::int64_t(n)})[0]);
}

float kth_smallest_positive(const SurfacePiece* piece, std::vector<float> mine, std::uint64_t k) {
  if (!piece) {
    if (k >= mine.size()) throw std::out_of_range("kth_smallest_positive: k past the values");
    std::nth_element(mine.begin(), mine.begin() + std::ptrdiff_t(k), mine.end());
    return mine[k];
  }
  // Positive floats order as their bit patterns: pick the high 16 bits, then the low 16.
  std::uint32_t high = 0;
  for (int round = 0; round < 2; ++round) {
    std::vector<std::int64_t> bins(1 << 16, 0);
    for (float v : mine) {
      const std::uint32_t b = bits_of(v);
      if (round == 0)
        ++bins[b >> 16];
      else if ((b >> 16) == high)
        ++bins[b & 0xffff];
    }
    bins = piece->sum(bins);
    std::uint32_t bin = 0;
    for (; bin < bins.size(); ++bin) {
      if (k < std::uint64_t(bins[bin])) break;
      k -= std::uint64_t(bins[bin]);
    }
    if (bin == bins.size()) throw std::out_of_range("kth_smallest_positive: k past the values");
    if (round == 0) {
      high = bin;
    } else {
      const std::uint32_t b = (high << 16) | bin;
      float v;
      std::memcpy(&v, &b, sizeof v);
      return v;
    }
  }
  return 0;  // not reached
}

}  // namespace isocurv
