// Degenerate and invalid input: finite output with flags, or one clear isocurv::Error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/estimate.h"
#include "curvature/reference.h"
#include "test_meshes.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;

// Both implementations, checked for finiteness and equal boundary flags.
std::pair<CurvatureField, CurvatureField> both(const Mesh& m, const curvature::Options& o = {}) {
  CurvatureField cl = curvature::estimate(m, Device::default_device(), o);
  CurvatureField ref = curvature::estimate_reference(m, o);
  EXPECT_EQ(cl.size(), m.vertex_count());
  EXPECT_EQ(ref.size(), m.vertex_count());
  EXPECT_TRUE(all_finite(cl));
  EXPECT_TRUE(all_finite(ref));
  EXPECT_EQ(cl.boundary, ref.boundary);
  return {std::move(cl), std::move(ref)};
}

TEST(Degenerate, EmptyMesh) {
  const auto [cl, ref] = both(Mesh{});
  EXPECT_EQ(cl.size(), 0u);
  EXPECT_TRUE(cl.normals.empty() && cl.dcurv.empty() && cl.boundary.empty());
}

TEST(Degenerate, VerticesWithoutTriangles) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}};
  const auto [cl, ref] = both(m);
  for (const CurvatureField* f : {&cl, &ref})
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(f->k1[i], 0.0f);
      EXPECT_EQ(f->area[i], 0.0f);
      EXPECT_EQ(f->normals[i], (Vec3f{0, 0, 0}));
      EXPECT_EQ(f->boundary[i], 0);
    }
}

TEST(Degenerate, SingleTriangleIsFlatAndOpen) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  const auto [cl, ref] = both(m);
  for (const CurvatureField* f : {&cl, &ref}) {
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(f->boundary[i], 1);
      EXPECT_NEAR(f->normals[i][2], 1.0f, 1e-7);
      EXPECT_NEAR(f->k1[i], 0.0f, 1e-6);
      EXPECT_NEAR(f->k2[i], 0.0f, 1e-6);
    }
    EXPECT_NEAR(f->area[0] + f->area[1] + f->area[2], 0.5f, 1e-7);
    EXPECT_NEAR(f->area[0], 0.25f, 1e-7);  // right angle at vertex 0: Voronoi, a quarter each
  }
}

// Repeated-index, coincident-vertex and collinear triangles on vertices of their own, plus an
// isolated vertex, leave the sphere's own vertices bit-identical and give finite values on theirs.
TEST(Degenerate, ZeroAreaTrianglesAndIsolatedVertices) {
  const Mesh sphere = icosphere(3);
  Mesh m = sphere;
  const std::uint32_t n = std::uint32_t(m.vertex_count());
  m.positions.push_back({3, 0, 0});  // n: coincident pair
  m.positions.push_back({3, 0, 0});  // n + 1
  m.positions.push_back({3, 1, 0});  // n + 2
  m.positions.push_back({4, 0, 0});  // n + 3
  m.positions.push_back({5, 0, 0});  // n + 4: collinear with n and n + 3
  m.positions.push_back({9, 9, 9});  // n + 5: isolated
  m.triangles.push_back({0, 0, 1});          // repeated index on sphere vertices: ignored
  m.triangles.push_back({n, n + 1, n + 2});  // two coincident corners
  m.triangles.push_back({n, n + 3, n + 4});  // collinear
  m.triangles.push_back({n + 2, n + 2, n + 2});
  const auto [cl, ref] = both(m);
  const CurvatureField plain = curvature::estimate(sphere, Device::default_device());
  for (std::size_t i = 0; i < sphere.vertex_count(); ++i) {
    ASSERT_EQ(cl.k1[i], plain.k1[i]);
    ASSERT_EQ(cl.k2[i], plain.k2[i]);
    ASSERT_EQ(cl.dir1[i], plain.dir1[i]);
    ASSERT_EQ(cl.dcurv[i], plain.dcurv[i]);
    ASSERT_EQ(cl.boundary[i], 0);
  }
  for (const CurvatureField* f : {&cl, &ref}) {
    for (std::uint32_t i = n; i < n + 6; ++i) {
      EXPECT_EQ(f->area[i], 0.0f);
      EXPECT_EQ(f->k1[i], 0.0f);
      EXPECT_EQ(f->k2[i], 0.0f);
    }
    EXPECT_EQ(f->boundary[n + 5], 0);
    EXPECT_EQ(f->boundary[n + 3], 1);  // its edges are used once, area or not
  }
}

// Degenerate triangles sharing vertices with good ones: the good geometry still decides.
TEST(Degenerate, NeedlesAttachedToSphere) {
  Mesh m = icosphere(3);
  const std::uint32_t n = std::uint32_t(m.vertex_count());
  const Vec3f a = m.positions[0], b = m.positions[1];
  m.positions.push_back({(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2});
  m.triangles.push_back({0, 1, n});  // (nearly) zero area, on existing vertices
  const auto [cl, ref] = both(m);
  EXPECT_NEAR(cl.k1[0], 1.0f, 1e-3);
  EXPECT_NEAR(ref.k1[0], 1.0f, 1e-3);
}

// A vertex split into two copies (a seam) makes both copies and their neighbours open.
TEST(Degenerate, DuplicateVertexMakesSeam) {
  Mesh m = icosphere(2);
  const std::uint32_t copy = std::uint32_t(m.vertex_count());
  m.positions.push_back(m.positions[0]);
  int moved = 0;
  for (Tri& t : m.triangles)
    for (auto& v : t)
      if (v == 0 && moved < 2) v = copy, ++moved;  // two of vertex 0's five triangles move
  const auto [cl, ref] = both(m);
  EXPECT_EQ(cl.boundary[0], 1);
  EXPECT_EQ(cl.boundary[copy], 1);
  EXPECT_EQ(cl.boundary[12], 0);  // a vertex far from the seam
}

TEST(Degenerate, OpenPatchBoundaryFlags) {
  const int n = 9;
  const auto [cl, ref] = both(quadric_patch(n, 1.0f, 0.3f, 0.2f));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool edge = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      EXPECT_EQ(cl.boundary[j * n + i], edge ? 1 : 0) << i << "," << j;
    }
}

TEST(Degenerate, GivenNormalsZeroOrNaNFallBackToMeshNormals) {
  const Mesh m = icosphere(2);
  std::vector<Vec3f> given(m.vertex_count());
  for (std::size_t i = 0; i < given.size(); ++i)
    for (int q = 0; q < 3; ++q) given[i][q] = 2 * m.positions[i][q];
  given[3] = {0, 0, 0};
  given[4] = {std::numeric_limits<float>::quiet_NaN(), 0, 0};
  curvature::Options o;
  o.vertex_normals = &given;
  const auto [cl, ref] = both(m, o);
  EXPECT_NEAR(cl.normals[3][0], m.positions[3][0], 1e-6);
  EXPECT_NEAR(cl.normals[4][2], m.positions[4][2], 1e-6);
  EXPECT_NEAR(cl.k1[4], 1.0f, 1e-4);
}

TEST(Invalid, IndexOutOfRangeThrows) {
  Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 3}};
  EXPECT_THROW(curvature::estimate(m, Device::default_device()), Error);
  EXPECT_THROW(curvature::estimate_reference(m), Error);
}

TEST(Invalid, NonFinitePositionThrows) {
  Mesh m = icosphere(1);
  m.positions[5][1] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(curvature::estimate(m, Device::default_device()), Error);
  m.positions[5][1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(curvature::estimate_reference(m), Error);
}

TEST(Invalid, WrongNormalCountThrows) {
  const Mesh m = icosphere(1);
  std::vector<Vec3f> given(m.vertex_count() - 1, Vec3f{0, 0, 1});
  curvature::Options o;
  o.vertex_normals = &given;
  EXPECT_THROW(curvature::estimate(m, Device::default_device(), o), Error);
  o.vertex_normals = nullptr;
  o.ao_scale = std::numeric_limits<float>::infinity();
  EXPECT_THROW(curvature::estimate_reference(m, o), Error);
}

}  // namespace
}  // namespace isocurv::test
