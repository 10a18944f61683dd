// lines::detail::build_vertex_pairs against the vertex -> corner adjacency it stands for: each
// vertex's row lists, in triangle order, every corner's two other vertices.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "curvature/vertex_corners.h"
#include "line_surfaces.h"
#include "lines/detail/vertex_pairs.h"

namespace isocurv::lines::detail {
namespace {

void expect_rows_of_corners(const Mesh& mesh, const VertexPairs& p) {
  curvature::VertexCorners vc;
  curvature::build_vertex_corners(mesh, vc);
  ASSERT_EQ(p.offsets, vc.offsets);
  ASSERT_EQ(p.pairs.size(), 2 * vc.corners.size());
  std::size_t wrong = 0;
  for (std::size_t k = 0; k < vc.corners.size(); ++k) {
    const Tri& t = mesh.triangles[vc.corners[k] / 3];
    const std::uint32_t j = vc.corners[k] % 3;
    wrong += p.pairs[2 * k] != t[(j + 1) % 3] || p.pairs[2 * k + 1] != t[(j + 2) % 3];
  }
  EXPECT_EQ(wrong, 0u);
}

TEST(LinesVertexPairs, RowsAreTheCornersOtherVertices) {
  Mesh m = test::icosphere(6);  // 81920 triangles: the parallel blocks
  ASSERT_GT(m.triangles.size(), 65536u);
  m.triangles[10] = {5, 5, 7};       // a repeated index: left out
  m.triangles.push_back({0, 1, 2});  // a non-manifold extra triangle
  VertexPairs p;
  build_vertex_pairs(m, p);
  expect_rows_of_corners(m, p);
  // The same rows whatever the number of threads, and from storage reused.
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    VertexPairs q;
    build_vertex_pairs(m, q);
    EXPECT_EQ(q.offsets, p.offsets);
    EXPECT_EQ(q.pairs, p.pairs);
  }
  const Mesh small = test::icosphere(2);
  build_vertex_pairs(small, p);
  expect_rows_of_corners(small, p);
}

TEST(LinesVertexPairs, IsolatedVerticesHaveEmptyRows) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  m.triangles = {{0, 1, 2}};
  VertexPairs p;
  build_vertex_pairs(m, p);
  EXPECT_EQ(p.offsets, (std::vector<std::uint32_t>{0, 1, 2, 3, 3}));
  EXPECT_EQ(p.pairs, (std::vector<std::uint32_t>{1, 2, 2, 0, 0, 1}));
}

}  // namespace
}  // namespace isocurv::lines::detail
