// What pictures are framed on (core/framing_points): specks far from the object are left out.
#include "core/framing_points.h"

#include <gtest/gtest.h>

#include <algorithm>

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
