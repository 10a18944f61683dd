// Disjoint sets (core/union_find.h): lowest-id roots whatever the order of the unions.
#include "core/union_find.h"

#include <gtest/gtest.h>

namespace isocurv {
namespace {

TEST(UnionFind, RootsAreTheLowestIdsWhateverTheOrder) {
  for (bool reversed : {false, true}) {
    UnionFind u(6);
    const std::uint32_t pairs[][2] = {{5, 3}, {3, 4}, {1, 2}};
    for (int k = 0; k < 3; ++k) {
      const auto& p = pairs[reversed ? 2 - k : k];
      u.unite(p[0], p[1]);
    }
    EXPECT_EQ(u.find(0), 0u);
    EXPECT_EQ(u.find(2), 1u);
    for (std::uint32_t x : {3u, 4u, 5u}) EXPECT_EQ(u.find(x), 3u);
    u.unite(4, 0);
    for (std::uint32_t x : {0u, 3u, 4u, 5u}) EXPECT_EQ(u.find(x), 0u);
    EXPECT_EQ(u.find(1), 1u);
  }
}

TEST(UnionFind, ResetMakesSingletonsAgain) {
  UnionFind u(3);
  u.unite(0, 2);
  u.reset(5);
  for (std::uint32_t x = 0; x < 5; ++x) EXPECT_EQ(u.find(x), x);
  u.unite(4, 1);
  EXPECT_EQ(u.find(4), 1u);
  u.reset(2);
  EXPECT_EQ(u.parent.size(), 2u);
}

}  // namespace
}  // namespace isocurv
