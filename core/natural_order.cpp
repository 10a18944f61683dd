#include "core/natural_order.h"

#include <algorithm>

namespace isocurv {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// -1, 0, +1: the digit runs a[i, i_end) and b[j, j_end) compared by value.
int compare_numbers(const std::string& a, std::size_t i, std::size_t i_end, const std::string& b,
                    std::size_t j, std::size_t j_end) {
  while (i + 1 < i_end && a[i] == '0') ++i;  // leading zeros (keep one digit)
  while (j + 1 < j_end && b[j] == '0') ++j;
  if (i_end - i != j_end - j) return i_end - i < j_end - j ? -1 : 1;
  for (; i < i_end; ++i, ++j)
    if (a[i] != b[j]) return a[i] < b[j] ? -1 : 1;
  return 0;
}

}  // namespace

bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (is_digit(a[i]) && is_digit(b[j])) {
      std::size_t i_end = i, j_end = j;
      while (i_end < a.size() && is_digit(a[i_end])) ++i_end;
      while (j_end < b.size() && is_digit(b[j_end])) ++j_end;
      const int c = compare_numbers(a, i, i_end, b, j, j_end);
      if (c != 0) return c < 0;
      i = i_end;
      j = j_end;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if (i < a.size() || j < b.size()) return j < b.size() && !(i < a.size());
  return a < b;  // same chunks (different zero padding): byte order keeps it strict
}

void natural_sort(std::vector<std::string>& names) {
  std::stable_sort(names.begin(), names.end(), natural_less);
}

}  // namespace isocurv
