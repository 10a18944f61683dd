#pragma once
// Comparing two meshers' outputs: the same triangles once vertices are matched.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

#include "core/mesh.h"

namespace isocurv::test {

/// The triangles of `a`, with vertex i renamed map[i], are those of `b` (as cyclic triples: the
/// same winding, any rotation, any order).
inline void expect_same_triangles(const Mesh& a, const Mesh& b, const std::vector<std::uint32_t>& map) {
  auto canon = [](Tri t) {  // rotate so the smallest index comes first, keeping the winding
    while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
    return t;
  };
  std::vector<Tri> ta, tb;
  for (const Tri& t : a.triangles) ta.push_back(canon({map[t[0]], map[t[1]], map[t[2]]}));
  for (const Tri& t : b.triangles) tb.push_back(canon(t));
  std::sort(ta.begin(), ta.end());
  std::sort(tb.begin(), tb.end());
  EXPECT_TRUE(ta == tb) << "the triangles differ";
}

/// Same vertex and triangle counts; vertices matched by edge key (both meshes need edge_keys),
/// positions equal to 1e-6 relative; then the same triangles.
inline void expect_same_mesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  ASSERT_EQ(a.edge_keys.size(), a.positions.size());
  ASSERT_EQ(b.edge_keys.size(), b.positions.size());
  std::map<std::uint64_t, std::uint32_t> b_of_key;
  for (std::uint32_t i = 0; i < b.edge_keys.size(); ++i) b_of_key[b.edge_keys[i]] = i;
  std::vector<std::uint32_t> map(a.positions.size());
  for (std::uint32_t i = 0; i < a.edge_keys.size(); ++i) {
    auto it = b_of_key.find(a.edge_keys[i]);
    ASSERT_NE(it, b_of_key.end()) << "vertex " << i << " has no twin";
    map[i] = it->second;
    for (int k = 0; k < 3; ++k) {
      const float pa = a.positions[i][k], pb = b.positions[it->second][k];
      ASSERT_NEAR(pa, pb, 1e-6 * std::max(1.0f, std::fabs(pb))) << "vertex " << i;
    }
  }
  expect_same_triangles(a, b, map);
}

}  // namespace isocurv::test
