// mc::check_mesh on hand-made meshes (orientation, offender lists) and mc::triangle_quality.
#include "mc/mesh_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mc/triangle_quality.h"
#include "volumes.h"

using namespace isocurv;

namespace {

// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), wound outward: signed volume 1/6.
Mesh tetrahedron(Vec3f shift = {0, 0, 0}) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (Vec3f& p : m.positions)
    for (int k = 0; k < 3; ++k) p[k] += shift[k];
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

}  // namespace

TEST(MeshCheck, ClosedComponentOrientationBySignedVolume) {
  const mc::MeshCheck good = mc::check_mesh(tetrahedron({100, -50, 7}));
  ASSERT_EQ(good.component_list.size(), 1u);
  EXPECT_TRUE(good.component_list[0].closed);
  EXPECT_NEAR(good.component_list[0].signed_volume, 1.0 / 6, 1e-9) << "independent of the position";
  EXPECT_EQ(good.closed_components(), 1u);
  EXPECT_EQ(good.inward_components(), 0u);

  Mesh inward = tetrahedron();
  for (Tri& t : inward.triangles) std::swap(t[1], t[2]);
  const mc::MeshCheck bad = mc::check_mesh(inward);
  EXPECT_TRUE(bad.oriented()) << "consistently oriented, only inward";
  EXPECT_TRUE(bad.watertight());
  EXPECT_EQ(bad.inward_components(), 1u);
  EXPECT_NEAR(bad.closed_signed_volume(), -1.0 / 6, 1e-9);

  // An open mesh (one face removed) gets no judgement.
  Mesh open = tetrahedron();
  open.triangles.pop_back();
  const mc::MeshCheck o = mc::check_mesh(open);
  EXPECT_EQ(o.closed_components(), 0u);
  EXPECT_FALSE(o.component_list.at(0).closed);
}

TEST(MeshCheck, CavityIsInwardInsideAnOutwardShell) {
  // A big outward tetrahedron with a small inward one inside: two closed components, one inward,
  // and the closed part as a whole is outward (a solid with a cavity).
  Mesh m = tetrahedron();
  for (Vec3f& p : m.positions)
    for (float& x : p) x *= 10;
  Mesh small = tetrahedron({1, 1, 1});
  const auto base = std::uint32_t(m.positions.size());
  for (const Vec3f& p : small.positions) m.positions.push_back(p);
  for (Tri t : small.triangles) m.triangles.push_back({t[0] + base, t[2] + base, t[1] + base});
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_EQ(c.components, 2u);
  EXPECT_EQ(c.closed_components(), 2u);
  EXPECT_EQ(c.inward_components(), 1u);
  EXPECT_GT(c.closed_signed_volume(), 0.0);
  EXPECT_EQ(c.component_list[1].first_vertex, base);
}

TEST(MeshCheck, NonManifoldEdgeIsJudgedForOrientation) {
  // Three triangles on edge 0-1: two traverse it 0->1. Non-manifold and misoriented.
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {1, 0, 4}};
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_EQ(c.non_manifold_edges, 1u);
  ASSERT_EQ(c.non_manifold.size(), 1u);
  EXPECT_EQ(c.non_manifold[0], (mc::VertexPair{0, 1}));
  EXPECT_EQ(c.misoriented_edges, 1u);
  ASSERT_EQ(c.misoriented.size(), 1u);
  EXPECT_EQ(c.misoriented[0], (mc::VertexPair{0, 1}));
  EXPECT_FALSE(c.oriented());

  // Two outward tetrahedra sharing an edge: four uses, two each way, so they pair up.
  Mesh two = tetrahedron();
  two.positions.push_back({1, 1, 0});
  two.positions.push_back({1, 1, 1});  // second tetrahedron 1, 2, 4, 5 shares edge 1-2
  const Tri extra[4] = {{1, 4, 2}, {1, 2, 5}, {1, 5, 4}, {2, 4, 5}};
  // Orient the second one outward by its signed volume.
  Mesh second;
  second.positions = two.positions;
  second.triangles.assign(extra, extra + 4);
  const bool flip = mc::check_mesh(second).closed_signed_volume() < 0;
  for (Tri t : extra) two.triangles.push_back(flip ? Tri{t[0], t[2], t[1]} : t);
  const mc::MeshCheck p = mc::check_mesh(two);
  EXPECT_EQ(p.non_manifold_edges, 1u);
  EXPECT_EQ(p.non_manifold.at(0), (mc::VertexPair{1, 2}));
  EXPECT_EQ(p.misoriented_edges, 0u) << "uses pair up in opposite directions";
}

TEST(MeshCheck, ListsDuplicatesWithTheirOriginal) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-0.0f, 0, 0}, {1, 1, 0}};
  m.triangles = {{0, 1, 2}, {3, 2, 4}};
  const mc::MeshCheck c = mc::check_mesh(m);
  EXPECT_EQ(c.duplicate_vertices, 2u);
  ASSERT_EQ(c.duplicates.size(), 2u);
  EXPECT_EQ(c.duplicates[0], (mc::VertexPair{3, 0})) << "-0 equals +0";
  EXPECT_EQ(c.duplicates[1], (mc::VertexPair{4, 2}));
}

TEST(TriangleQuality, AreasAnglesAndCounts) {
  Mesh m;
  // A right isosceles triangle (area 0.5, smallest angle 45), a sliver (area 5e-5, smallest angle
  // ~0.0115 degrees), and one with a repeated vertex (area 0, angle 0).
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0.5f, 1e-4f, 1}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  mc::TriangleQuality q = mc::triangle_quality(m, 1.0);
  EXPECT_EQ(q.triangles, 2u);
  EXPECT_NEAR(q.min_area, 5e-5, 1e-7);
  EXPECT_NEAR(q.min_angle, std::atan(2e-4) * 180 / M_PI, 1e-4);
  EXPECT_EQ(q.small, 1u) << "5e-5 < 1e-4";
  EXPECT_EQ(q.thin, 1u);
  // A larger unit counts the right triangle as small too (0.5 < 1e-4 * 1e4 = 1).
  EXPECT_EQ(mc::triangle_quality(m, 1e4).small, 2u);
  m.triangles.push_back({0, 0, 1});
  q = mc::triangle_quality(m, 1.0);
  EXPECT_EQ(q.min_area, 0.0);
  EXPECT_EQ(q.min_angle, 0.0);
  EXPECT_EQ(q.thin, 2u);
  EXPECT_EQ(mc::triangle_quality(Mesh{}, 1.0).triangles, 0u);
}

TEST(TriangleQuality, VoxelFaceAreaIsTheGeometricMean) {
  const volume::Volume v =
      test::sampled([](double, double, double) { return 0.f; }, {4, 4, 4}, {1, 2, 4});
  EXPECT_NEAR(mc::voxel_face_area(v), 4.0, 1e-9) << "(1*2*4)^(2/3)";
}
