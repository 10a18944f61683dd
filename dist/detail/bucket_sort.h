#pragma once
// Sorting many items whose leading key is a small integer (a vertex index): a counting sort by
// that key, then a comparison sort within each bucket (a vertex starts a handful of edges or
// triangles), linear where std::sort of millions of items took a third of a second.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/huge_pages.h"

namespace isocurv::dist::detail {

/// Sorts `items` by (bucket_of(item), then `less` within a bucket); bucket_of(item) < buckets.
/// The same order as std::sort with that lexicographic comparison (up to ties of `less`).
template <class T, class Bucket, class Less>
void bucket_sort(std::vector<T>& items, std::size_t buckets, Bucket bucket_of, Less less) {
  std::vector<std::size_t> start(buckets + 1, 0);
  for (const T& item : items) ++start[std::size_t(bucket_of(item)) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<T> sorted;
  resize_in_huge_pages(sorted, items.size());  // first touches of small pages are slow on VMs
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (const T& item : items) sorted[next[std::size_t(bucket_of(item))]++] = item;
  for (std::size_t b = 0; b < buckets; ++b)
    if (start[b + 1] - start[b] > 1)
      std::sort(sorted.begin() + std::ptrdiff_t(start[b]), sorted.begin() + std::ptrdiff_t(start[b + 1]), less);
  items.swap(sorted);
}

}  // namespace isocurv::dist::detail
