// measure::object_measures on meshes whose measures are known by hand: unit cubes (area 6,
// volume 1, Euler 2), two of them (two components, larger first), one cut open, and the
// integrals of a field given per vertex.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "measure/object_measures.h"

namespace isocurv::measure {
namespace {

/// An axis-aligned cube of edge `a` at `o`, outward triangles, appended to `m`.
void add_cube(Mesh& m, float a, const Vec3f& o) {
  const auto base = std::uint32_t(m.positions.size());
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({o[0] + a * (i & 1), o[1] + a * ((i >> 1) & 1), o[2] + a * ((i >> 2) & 1)});
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({base + q[0], base + q[1], base + q[2]});
    m.triangles.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

curvature::CurvatureField field_for(const Mesh& m, float h, float k, float area) {
  curvature::CurvatureField f;
  f.H.assign(m.positions.size(), h);
  f.K.assign(m.positions.size(), k);
  f.area.assign(m.positions.size(), area);
  return f;
}

TEST(ObjectMeasures, CubesByHand) {
  Mesh m;
  add_cube(m, 1.0f, {5, 5, 5});
  add_cube(m, 2.0f, {0, 0, 0});  // the larger one, listed first
  const auto objects = object_measures(m, field_for(m, 0.5f, 0.25f, 2.0f));
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_NEAR(objects[0].area, 24, 1e-9);
  EXPECT_NEAR(objects[0].volume, 8, 1e-9);
  EXPECT_NEAR(objects[1].area, 6, 1e-9);
  EXPECT_NEAR(objects[1].volume, 1, 1e-9);
  for (const ObjectMeasures& o : objects) {
    EXPECT_TRUE(o.closed);
    EXPECT_EQ(o.vertices, 8u);
    EXPECT_EQ(o.edges, 18u);
    EXPECT_EQ(o.euler, 2);
    EXPECT_EQ(o.genus(), 0);
    EXPECT_NEAR(o.integral_H, 8 * 0.5 * 2, 1e-9);
    EXPECT_NEAR(o.integral_K, 8 * 0.25 * 2, 1e-9);
    // 4 against 4 pi: the gap says how far the curvature is from Gauss-Bonnet.
    EXPECT_NEAR(o.gauss_bonnet_gap(), (4 - 4 * M_PI) / (4 * M_PI), 1e-12);
  }
  EXPECT_EQ(objects[1].box, (std::array<double, 6>{5, 6, 5, 6, 5, 6}));
  const ObjectMeasures all = total(objects);
  EXPECT_NEAR(all.volume, 9, 1e-9);
  EXPECT_EQ(all.euler, 4);
  EXPECT_TRUE(all.closed);
}

TEST(ObjectMeasures, ACutComponentIsOpenAndUnmeasuredVerticesAreLeftOut) {
  Mesh m;
  add_cube(m, 1.0f, {0, 0, 0});
  m.triangles.pop_back();  // one triangle less: three boundary edges
  curvature::CurvatureField f = field_for(m, 1.0f, 1.0f, 1.0f);
  f.unreliable.assign(m.positions.size(), 0);
  f.unreliable[0] = 1;
  const auto objects = object_measures(m, f);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_FALSE(objects[0].closed);
  EXPECT_EQ(objects[0].boundary_edges, 3u);
  EXPECT_EQ(objects[0].genus(), -1);
  EXPECT_TRUE(std::isnan(objects[0].gauss_bonnet_gap()));
  EXPECT_EQ(objects[0].unmeasured, 1u);
  EXPECT_NEAR(objects[0].integral_H, 7, 1e-9);
  EXPECT_NEAR(objects[0].area, 5.5, 1e-9);
}

TEST(ObjectMeasures, WithoutAnAreaArrayTheTrianglesShareTheirAreaAndBadFieldsAreErrors) {
  Mesh m;
  add_cube(m, 1.0f, {0, 0, 0});
  curvature::CurvatureField f = field_for(m, 1.0f, 0.0f, 0.0f);
  f.area.clear();
  EXPECT_NEAR(object_measures(m, f)[0].integral_H, 6, 1e-9);  // H = 1 over area 6
  f.K.pop_back();
  EXPECT_THROW(object_measures(m, f), Error);
  EXPECT_TRUE(object_measures(Mesh{}, curvature::CurvatureField{}).empty());
}

// The integral of K is the per-vertex curvature's own total: a K that keeps Gauss-Bonnet with its
// vertex areas (here each cube corner's angle defect pi / 2 over its area) has a gap of zero,
// also where normals make the patches curved (whose areas differ from the vertices').
TEST(ObjectMeasures, AGaussBonnetKeepingCurvatureHasNoGapOnCurvedPatches) {
  Mesh m;
  add_cube(m, 1.0f, {0, 0, 0});
  curvature::CurvatureField f = field_for(m, 1.0f, 0.0f, 0.0f);
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    f.area[i] = 0.5f + 0.125f * float(i);  // any areas: K carries the defect over them
    f.K[i] = float(M_PI / 2) / f.area[i];
    Vec3f n;
    for (int c = 0; c < 3; ++c) n[c] = (m.positions[i][c] - 0.5f) / std::sqrt(0.75f);
    f.normals.push_back(n);
  }
  const auto objects = object_measures(m, f);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_NEAR(objects[0].gauss_bonnet_gap(), 0, 1e-6);
  EXPECT_GT(objects[0].area, 6.0) << "the patches bulge out along the normals";
  EXPECT_NEAR(objects[0].mesh_area, 6, 1e-9) << "the mesh's own triangles";
}

// A component smaller than its curvature's scale resolves is said to be (the Scale array).
TEST(ObjectMeasures, AComponentBelowItsScaleIsNotResolved) {
  Mesh m;
  add_cube(m, 1.0f, {0, 0, 0});
  curvature::CurvatureField f = field_for(m, 1.0f, 0.0f, 1.0f);
  EXPECT_TRUE(object_measures(m, f)[0].resolved) << "no Scale array: nothing to compare";
  f.extra.push_back({"Scale", std::vector<float>(m.positions.size(), 0.1f)});
  EXPECT_TRUE(object_measures(m, f)[0].resolved);
  EXPECT_NEAR(object_measures(m, f)[0].scale, 0.1, 1e-7);
  f.extra.back().values[3] = 0.5f;  // the largest scale counts
  const ObjectMeasures o = object_measures(m, f)[0];
  EXPECT_FALSE(o.resolved);
  EXPECT_NEAR(o.scale, 0.5, 1e-7);
  EXPECT_FALSE(total({o}).resolved);
}

}  // namespace
}  // namespace isocurv::measure
