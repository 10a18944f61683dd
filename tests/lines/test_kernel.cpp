// The OpenCL extraction against the double reference, and its determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "core/cl_device.h"
#include "line_surfaces.h"
#include "lines/extract.h"
#include "lines/reference.h"

namespace isocurv::lines {
namespace {

// A bumpy closed surface (every line type appears) seen in perspective.
test::Surface bumpy() {
  Mesh m = test::icosphere(5);
  for (Vec3f &p : m.positions) {
    const double r = 1 + 0.12 * std::sin(5 * p[0]) * std::cos(4 * p[1]) +
                     0.08 * std::sin(6 * p[2]);
    for (float &c : p)
      c = float(c * r);
  }
  return test::with_curvature(std::move(m));
}

Camera perspective() {
  Camera cam;
  cam.position = {2.5, -3.5, 2};
  cam.view_up = {0, 0, 1};
  return cam;
}

TEST(LinesKernel, MatchesTheReference) {
  const test::Surface s = bumpy();
  Options o;
  o.lines = parse_line_selection("all");
  o.ridge_threshold =
      0.5; // enough ridges and valleys on this bump field to compare
  const double edge = test::mean_edge(s.mesh);
  for (bool ortho : {false, true}) {
    Camera cam = perspective();
    cam.ortho = ortho;
    const Segments ref = extract_reference(s.mesh, s.field, cam, o);
    const Segments dev =
        extract(s.mesh, s.field, cam, o, Device::default_device());
    std::map<std::pair<std::uint32_t, int>, const Segment *> by_face;
    for (const Segment &g : dev)
      by_face[{g.face, int(g.type)}] = &g;
    std::size_t per_type[kLineTypeCount] = {0, 0, 0, 0},
                far_type[kLineTypeCount] = {0, 0, 0, 0}, missing = 0, far = 0;
    for (const Segment &g : ref) {
      ++per_type[int(g.type)];
      const auto it = by_face.find({g.face, int(g.type)});
      if (it == by_face.end()) {
        ++missing;
        continue;
      }
      const Segment &h = *it->second;
      // a crossing within float rounding of a vertex is keyed by the vertex on
      // one side only
      if (test::seg_length(g.a, h.a) > 1e-3 * edge ||
          test::seg_length(g.b, h.b) > 1e-3 * edge ||
          std::fabs(g.strength - h.strength) > 1e-3 || g.edge_a != h.edge_a ||
          g.edge_b != h.edge_b) {
        ++far, ++far_type[int(g.type)];
      }
    }
    for (int t = 0; t < kLineTypeCount; ++t)
      EXPECT_GT(per_type[t], 10u)
          << "type " << t << (ortho ? " ortho" : " perspective");
    // float against double: a face whose test is within rounding of its
    // threshold may differ
    const double n = double(ref.size());
    EXPECT_LE(missing, 0.005 * n + 2);
    EXPECT_LE(double(dev.size()), n * 1.005 + 2);
    EXPECT_LE(far, 0.005 * n + 2);
    std::printf("%s: %zu reference segments, %zu missing, %zu apart\n",
                ortho ? "ortho" : "perspective", ref.size(), missing, far);
    for (int t = 0; t < kLineTypeCount; ++t)
      std::printf("  type %d: %zu of %zu apart\n", t, far_type[t], per_type[t]);
  }
}

TEST(LinesKernel, Deterministic) {
  const test::Surface s = bumpy();
  Options o;
  o.lines = parse_line_selection("all");
  Device &d = Device::default_device();
  const Segments a = extract(s.mesh, s.field, perspective(), o, d);
  const Segments b = extract(s.mesh, s.field, perspective(), o, d);
  // reusing the uploaded mesh, as the explorer does when only its camera moves
  const Segments c =
      extract(s.mesh, s.field, perspective(), o, d, nullptr, false);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (const Segments *x : {&b, &c}) {
      const Segment &g = (*x)[i];
      EXPECT_EQ(g.a, a[i].a);
      EXPECT_EQ(g.b, a[i].b);
      EXPECT_EQ(g.face, a[i].face);
      EXPECT_EQ(g.type, a[i].type);
      EXPECT_EQ(g.strength, a[i].strength);
    }
  }
  for (std::size_t i = 1; i < a.size(); ++i)
    EXPECT_LE(a[i - 1].face, a[i].face); // face order
}

// Contours from a field without directions or derivative (prantl2, prantl3, meyer): the kernel
// and the reference give the contours the full field gives, segment for segment.
TEST(LinesKernel, ContoursWithoutDirectionsMatchTheFullField) {
  const test::Surface full = bumpy();
  test::Surface bare = bumpy();
  bare.field.dir1.clear();
  bare.field.dir2.clear();
  bare.field.dcurv.clear();
  Options o;
  o.lines = parse_line_selection("contours");
  Device &d = Device::default_device();
  for (bool ortho : {false, true}) {
    Camera cam = perspective();
    cam.ortho = ortho;
    const Segments want = extract(full.mesh, full.field, cam, o, d);
    ASSERT_GT(want.size(), 50u);
    for (const Segments &got :
         {extract(bare.mesh, bare.field, cam, o, d), extract_reference(bare.mesh, bare.field, cam, o)}) {
      ASSERT_EQ(got.size(), want.size()) << (ortho ? "ortho" : "perspective");
      for (std::size_t i = 0; i < got.size(); ++i) {
        EXPECT_EQ(got[i].face, want[i].face);
        EXPECT_EQ(got[i].edge_a, want[i].edge_a);
        EXPECT_EQ(got[i].edge_b, want[i].edge_b);
        EXPECT_LT(test::seg_length(got[i].a, want[i].a), 1e-3 * test::mean_edge(full.mesh));
      }
    }
  }
  // Group sizes above 1: the kernel path ran with 64-wide groups (core/cl_launch.h) over a vertex
  // count that is not a multiple of 64.
  EXPECT_NE(bare.mesh.vertex_count() % 64, 0u);
}

TEST(LinesKernel, EmptyMeshAndNothingSelected) {
  Options o;
  Mesh empty;
  curvature::CurvatureField none;
  EXPECT_TRUE(
      extract(empty, none, Camera{}, o, Device::default_device()).empty());
  const test::Surface s = test::with_curvature(test::icosphere(2));
  o.lines = LineSelection{};
  EXPECT_TRUE(
      extract(s.mesh, s.field, Camera{}, o, Device::default_device()).empty());
}

} // namespace
} // namespace isocurv::lines
