#pragma once
// UnionFind: disjoint sets of the ids 0 .. n-1 (connected components of a mesh's vertices),
// header-only. Path halving on find; unite makes the lower of the two roots the root, so that
// every set's root is its lowest id whatever the order of the unions (deterministic, and a
// component's root is its first vertex). Not thread-safe. Tested in tests/core/test_union_find.cpp.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace isocurv {

struct UnionFind {
  std::vector<std::uint32_t> parent;  ///< parent[x] == x for a root

  /// n singletons, {0}, {1}, ..., {n - 1}.
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }

  /// n singletons again, keeping the storage (for a union-find reused per item of a loop).
  void reset(std::size_t n) {
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
  }

  /// The root of x's set: its lowest id.
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }

  /// Merges the sets of a and b (nothing when they are one already).
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace isocurv
