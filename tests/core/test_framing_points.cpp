// What pictures are framed on (core/framing_points): specks far from the object are left out.
#include "core/framing_points.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace isocurv {
namespace {

// Appends an axis-aligned closed box [lo, hi] (12 triangles) to `m`.
void add_box(Mesh& m, const Vec3f& lo, const Vec3f& hi) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (int c = 0; c < 8; ++c)
    m.positions.push_back({(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({base + q[0], base + q[1], base + q[2]});
    m.triangles.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

// Appends the box [lo, hi] with each face cut into squares of side about `h` (two triangles
// each), its vertices shared (one closed component).
void add_fine_box(Mesh& m, const Vec3f& lo, const Vec3f& hi, float h) {
  std::map<std::array<float, 3>, std::uint32_t> ids;
  auto id = [&](std::array<float, 3> p) {
    const auto [it, fresh] = ids.emplace(p, std::uint32_t(m.positions.size()));
    if (fresh) m.positions.push_back({p[0], p[1], p[2]});
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const int nu = std::max(1, int(std::lround((hi[u] - lo[u]) / h)));
      const int nv = std::max(1, int(std::lround((hi[v] - lo[v]) / h)));
      auto at = [&](int i, int j) {
        std::array<float, 3> p{};
        p[axis] = side ? hi[axis] : lo[axis];
        p[u] = lo[u] + (hi[u] - lo[u]) * float(i) / float(nu);
        p[v] = lo[v] + (hi[v] - lo[v]) * float(j) / float(nv);
        return id(p);
      };
      for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
          m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
          m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    }
}

double max_x(const std::vector<std::array<double, 3>>& p) {
  double m = -1e300;
  for (const auto& q : p) m = std::max(m, q[0]);
  return m;
}
double min_x(const std::vector<std::array<double, 3>>& p) {
  double m = 1e300;
  for (const auto& q : p) m = std::min(m, q[0]);
  return m;
}

TEST(FramingPoints, LeaveOutSpecksButKeepComparablePieces) {
  Mesh m;
  add_box(m, {0, 0, 0}, {10, 10, 10});          // the object: area 600
  add_box(m, {50, 0, 0}, {50.5f, 0.5f, 0.5f});  // a speck far away: area 1.5, 0.25% of it
  std::vector<std::array<double, 3>> p = framing_points(m);
  EXPECT_EQ(p.size(), 8u);
  EXPECT_DOUBLE_EQ(max_x(p), 10.0);

  add_box(m, {-30, 0, 0}, {-28, 2, 2});  // area 24 = 4% of the object: a piece of it
  p = framing_points(m);
  EXPECT_EQ(p.size(), 16u);
  EXPECT_DOUBLE_EQ(min_x(p), -30.0);
  EXPECT_DOUBLE_EQ(max_x(p), 10.0);  // the speck is still left out
}

TEST(FramingPoints, ThickLongPartsAreFramed) {
  // The object: a box of side 100 (12 triangles: the mean edge is the finely cut parts').
  Mesh m;
  add_box(m, {0, 0, 0}, {100, 100, 100});
  // A rod beside it, as an MR's fiducial marker: 3 x 3 x 40, area 498 = 0.8% of the object's but
  // 23% of its extent and about 22 mean edges thick: a part of the picture.
  add_fine_box(m, {110, 0, 0}, {113, 3, 40}, 0.5f);
  // A streak one cell across (0.5 x 0.5 x 40, as noise along a volume's edge): as long, but
  // 3.5 mean edges thick: a speck.
  add_fine_box(m, {-20, 0, 0}, {-19.5f, 0.5f, 40}, 0.5f);
  const std::vector<std::array<double, 3>> p = framing_points(m);
  EXPECT_DOUBLE_EQ(max_x(p), 113.0);
  EXPECT_DOUBLE_EQ(min_x(p), 0.0);
}

TEST(FramingPoints, MeshesWithoutTrianglesOrVertices) {
  Mesh points;
  points.positions = {{1, 2, 3}, {-1, 5, 0}};
  EXPECT_EQ(framing_points(points).size(), 2u);
  EXPECT_TRUE(framing_points(Mesh{}).empty());
  Mesh bad;  // an index out of range is skipped, not read
  bad.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  bad.triangles = {{0, 1, 7}, {0, 1, 2}};
  EXPECT_EQ(framing_points(bad).size(), 3u);  // the unused vertex is a zero-area component
}

}  // namespace
}  // namespace isocurv
