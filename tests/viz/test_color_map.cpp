// Colour map, ranges, quantities and glyphs: no rendering needed.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkColorTransferFunction.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include "core/error.h"
#include "test_surfaces.h"
#include "viz/color_map.h"
#include "viz/direction_glyphs.h"
#include "viz/quantity.h"

using namespace isocurv;

TEST(VizColorMap, SignedRangeIsSymmetricAndClampsOutliers) {
  std::vector<float> v;
  for (int i = 0; i < 1000; ++i) v.push_back(-0.5f + i / 1000.f);  // [-0.5, 0.5)
  v[10] = 1000.f;                                                    // outliers
  v[20] = -500.f;
  v.push_back(NAN);
  const viz::ColorRange r = viz::color_range(v, "H", 2);
  EXPECT_DOUBLE_EQ(r.lo, -r.hi);
  EXPECT_NEAR(r.hi, 0.49, 0.02);
  const viz::ColorRange all = viz::color_range(v, "H", 0);
  EXPECT_DOUBLE_EQ(all.hi, 1000.0);
}

TEST(VizColorMap, UnsignedAndShapeIndexRanges) {
  std::vector<float> v;
  for (int i = 0; i <= 100; ++i) v.push_back(2.f + i / 100.f);
  const viz::ColorRange c = viz::color_range(v, "Curvedness", 2);
  EXPECT_NEAR(c.lo, 2.02, 1e-6);
  EXPECT_NEAR(c.hi, 2.98, 1e-6);
  const viz::ColorRange s = viz::color_range(v, "ShapeIndex", 2);
  EXPECT_EQ(s.lo, -1);
  EXPECT_EQ(s.hi, 1);
  const viz::ColorRange flat = viz::color_range(std::vector<float>(10, 0.f), "K", 2);
  EXPECT_LT(flat.lo, 0);
  EXPECT_GT(flat.hi, 0);
}

TEST(VizColorMap, BlueNegativeGreenZeroRedPositiveAndAoDarkens) {
  const viz::ColorRange range{-1, 1};
  auto map = viz::make_color_map(range);
  const std::vector<float> values = {-1, 0, 1, 5, NAN};
  auto colors = viz::vertex_colors(values, range, map);
  auto rgb = [&](vtkUnsignedCharArray* a, int i) {
    return std::array<int, 3>{a->GetValue(3 * i), a->GetValue(3 * i + 1), a->GetValue(3 * i + 2)};
  };
  const auto neg = rgb(colors, 0), zero = rgb(colors, 1), pos = rgb(colors, 2), clamped = rgb(colors, 3),
             nan = rgb(colors, 4);
  EXPECT_GT(neg[2], neg[0] + 100);
  EXPECT_GT(zero[1], zero[0] + 100);
  EXPECT_GT(zero[1], zero[2] + 100);
  EXPECT_GT(pos[0], pos[2] + 100);
  EXPECT_EQ(clamped, pos);
  EXPECT_EQ(nan[0], nan[1]);
  EXPECT_STREQ(colors->GetName(), "Colors");

  const std::vector<float> ao = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
  auto shaded = viz::vertex_colors(values, range, map, &ao);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rgb(shaded, 2)[c], pos[c] / 2.0, 1.0);
}

TEST(VizQuantity, NamesAndMissingArrays) {
  const auto torus = test::torus(16, 8);
  EXPECT_EQ(viz::canonical_quantity("shapeindex"), "ShapeIndex");
  EXPECT_EQ(viz::canonical_quantity("K"), "K");
  EXPECT_EQ(&viz::quantity_values(torus.field, "k2"), &torus.field.k2);
  EXPECT_THROW(viz::canonical_quantity("Gauss"), Error);
  curvature::CurvatureField empty;
  EXPECT_THROW(viz::quantity_values(empty, "H"), Error);
  EXPECT_TRUE(viz::is_signed_quantity("K"));
  EXPECT_FALSE(viz::is_signed_quantity("AO"));
}

TEST(VizDirectionGlyphs, EvenSubsampleTwoColouredSegmentsPerVertex) {
  const auto s = test::saddle(64);
  auto glyphs = viz::direction_glyphs(s.mesh, s.field);
  const vtkIdType lines = glyphs->GetNumberOfLines();
  EXPECT_GT(lines, 100);
  EXPECT_LT(lines, static_cast<vtkIdType>(s.mesh.vertex_count()));  // a subsample
  EXPECT_EQ(lines % 2, 0);
  auto* colors = vtkUnsignedCharArray::SafeDownCast(glyphs->GetCellData()->GetScalars());
  ASSERT_NE(colors, nullptr);
  EXPECT_EQ(colors->GetValue(0), viz::kDir1Color[0]);
  EXPECT_EQ(colors->GetValue(3), viz::kDir2Color[0]);
  // segment length relates to the mesh resolution
  double a[3], b[3];
  glyphs->GetPoint(0, a);
  glyphs->GetPoint(1, b);
  const double len = std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  const double edge = mean_edge_length(s.mesh);
  EXPECT_GT(len, 1.0 * edge);
  EXPECT_LT(len, 4.0 * edge);

  curvature::CurvatureField no_dirs = s.field;
  no_dirs.dir1.clear();
  EXPECT_EQ(viz::direction_glyphs(s.mesh, no_dirs)->GetNumberOfLines(), 0);
}
