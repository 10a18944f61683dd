// Colour map, ranges, quantities and glyphs: no rendering needed.
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkColorTransferFunction.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>

#include "core/error.h"
#include "test_surfaces.h"
#include "viz/color_map.h"
#include "viz/direction_glyphs.h"
#include "viz/picture_layout.h"
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
  const viz::ColorRange c = viz::color_range(v, "Curvedness", 2);  // unsigned: from zero
  EXPECT_EQ(c.lo, 0.0);
  EXPECT_NEAR(c.hi, 2.98, 1e-6);
  const viz::ColorRange s = viz::color_range(v, "ShapeIndex", 2);
  EXPECT_EQ(s.lo, -1);
  EXPECT_EQ(s.hi, 1);
  const viz::ColorRange flat = viz::color_range(std::vector<float>(10, 0.f), "K", 2);
  EXPECT_LT(flat.lo, 0);
  EXPECT_GT(flat.hi, 0);
}

TEST(VizColorMap, PapersMapIsBlueNegativeGreenZeroRedPositiveAndAoDarkens) {
  const viz::ColorRange range{-1, 1};
  auto map = viz::make_color_map(range, "bgr");
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

namespace {

std::array<int, 3> colour_of(float value, const viz::ColorRange& range, const std::string& cmap) {
  auto map = viz::make_color_map(range, cmap);
  auto c = viz::vertex_colors({value}, range, map);
  return {c->GetValue(0), c->GetValue(1), c->GetValue(2)};
}

}  // namespace

TEST(VizColorMap, DivergingNeutralLandsAtZeroForEveryRange) {
  // ColorBrewer RdBu's light neutral #f7f7f7 sits at zero whether the range is symmetric,
  // lopsided or one-signed; blue below, red above.
  for (const viz::ColorRange r : {viz::ColorRange{-1, 1}, viz::ColorRange{-0.2, 3}, viz::ColorRange{0, 2},
                                  viz::ColorRange{-5, 0}}) {
    const auto zero = colour_of(0.f, r, "diverging");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(zero[c], 0xf7, 2) << r.lo << " " << r.hi;
    if (r.lo < 0) {
      const auto neg = colour_of(static_cast<float>(r.lo), r, "diverging");
      EXPECT_GT(neg[2], neg[0]) << "negative end is blue";
    }
    if (r.hi > 0) {
      const auto pos = colour_of(static_cast<float>(r.hi), r, "diverging");
      EXPECT_GT(pos[0], pos[2]) << "positive end is red";
    }
  }
  const auto blue = colour_of(-1.f, {-1, 1}, "diverging"), red = colour_of(1.f, {-1, 1}, "diverging");
  EXPECT_GT(blue[2], blue[0] + 100);
  EXPECT_GT(red[0], red[2] + 100);
  // the symmetric range reaches both saturated ends; a one-signed one only its half
  EXPECT_EQ(colour_of(2.f, {0, 2}, "diverging"), colour_of(2.f, {-2, 2}, "diverging"));
  EXPECT_EQ(colour_of(1.f, {0, 2}, "diverging"), colour_of(1.f, {-2, 2}, "diverging"));
}

TEST(VizColorMap, FixedRangeIsHonouredExactly) {
  std::vector<float> v;
  for (int i = 0; i < 500; ++i) v.push_back(-3.f + i * 0.02f);
  const viz::ColorRange fixed{-0.25, 0.75};
  const viz::ColorRange r = viz::color_range(v, "H", 2, fixed);
  EXPECT_EQ(r.lo, -0.25);
  EXPECT_EQ(r.hi, 0.75);
  // values at and beyond the ends take the end colours; inside the range they differ
  const auto lo = colour_of(-0.25f, r, "viridis"), hi = colour_of(0.75f, r, "viridis");
  EXPECT_EQ(colour_of(-9.f, r, "viridis"), lo);
  EXPECT_EQ(colour_of(9.f, r, "viridis"), hi);
  EXPECT_NE(colour_of(-0.2f, r, "viridis"), lo);
  EXPECT_NE(colour_of(0.7f, r, "viridis"), hi);
  EXPECT_THROW(viz::color_range(v, "H", 2, viz::ColorRange{1, 1}), Error);
  EXPECT_THROW(viz::color_range(v, "H", 2, viz::ColorRange{2, 1}), Error);
}

TEST(VizColorMap, OneSignedQuantitiesRunFromZeroToTheExtreme) {
  std::vector<float> pos, neg;
  for (int i = 1; i <= 100; ++i) pos.push_back(0.5f + i * 0.01f), neg.push_back(-0.5f - i * 0.01f);
  const viz::ColorRange p = viz::color_range(pos, "K", 2), n = viz::color_range(neg, "k2", 2);
  EXPECT_EQ(p.lo, 0.0);
  EXPECT_NEAR(p.hi, 1.48, 1e-6);
  EXPECT_NEAR(n.lo, -1.48, 1e-6);
  EXPECT_EQ(n.hi, 0.0);
  EXPECT_EQ(viz::color_range(pos, "AO", 2).lo, 0.0);
  EXPECT_EQ(viz::color_range(pos, "AO", 2).hi, 1.0);
}

TEST(VizColorMap, AutoMapsByQuantityAndAoIsGrey) {
  EXPECT_EQ(viz::resolve_color_map("auto", "H"), "diverging");
  EXPECT_EQ(viz::resolve_color_map("auto", "ShapeIndex"), "diverging");
  EXPECT_EQ(viz::resolve_color_map("auto", "Curvedness"), "viridis");
  EXPECT_EQ(viz::resolve_color_map("auto", "AO"), "grey");
  EXPECT_EQ(viz::resolve_color_map("bgr", "AO"), "bgr");
  EXPECT_THROW(viz::resolve_color_map("rainbow", "H"), Error);
  for (float a : {0.f, 0.3f, 0.8f, 1.f}) {
    const auto g = colour_of(a, {0, 1}, "grey");
    EXPECT_EQ(g[0], g[1]);
    EXPECT_EQ(g[1], g[2]);
    EXPECT_NEAR(g[0], 255 * a, 1.0);
  }
  // viridis is perceptually ordered: its luminance rises monotonically
  double last = -1;
  for (int i = 0; i <= 20; ++i) {
    const auto c = colour_of(i / 20.f, {0, 1}, "viridis");
    const double l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(l, last) << i;
    last = l;
  }
}

TEST(VizQuantity, NamesAndMissingArrays) {
  const auto torus = test::torus(16, 8);
  EXPECT_EQ(viz::canonical_quantity("shapeindex"), "ShapeIndex");
  EXPECT_EQ(viz::canonical_quantity("K"), "K");
  EXPECT_EQ(viz::quantity_values(torus.field, "k2"), torus.field.k2);
  EXPECT_EQ(viz::canonical_quantity("Gauss"), "Gauss") << "other names are array names";
  EXPECT_THROW(viz::quantity_values(torus.field, "Gauss"), Error);
  curvature::CurvatureField empty;
  EXPECT_THROW(viz::quantity_values(empty, "H"), Error);
  EXPECT_TRUE(viz::is_signed_quantity("K"));
  EXPECT_FALSE(viz::is_signed_quantity("AO"));
  EXPECT_EQ(viz::quantity_unit("H", "mm"), "1/mm");
  EXPECT_EQ(viz::quantity_unit("K", ""), "1/length\u00b2");
  EXPECT_EQ(viz::quantity_unit("ShapeIndex", "mm"), "");
}

TEST(VizQuantity, AnyArrayByItsNameKindAndSuffix) {
  using viz::QuantityKind;
  EXPECT_EQ(viz::quantity_kind("H_s2"), QuantityKind::curvature);
  EXPECT_EQ(viz::quantity_kind("H_ii_r0.3"), QuantityKind::curvature);
  EXPECT_EQ(viz::quantity_kind("K_ii"), QuantityKind::curvature);
  EXPECT_EQ(viz::quantity_kind("k1_s4"), QuantityKind::curvature);
  EXPECT_EQ(viz::quantity_kind("Hattori"), QuantityKind::other) << "H only as a word";
  EXPECT_EQ(viz::quantity_kind("SI_ii"), QuantityKind::shape_index);
  EXPECT_EQ(viz::quantity_kind("ShapeIndex_s2"), QuantityKind::shape_index);
  EXPECT_EQ(viz::quantity_kind("Unreliable_s2"), QuantityKind::flag);
  EXPECT_EQ(viz::quantity_kind("FeatureBoundary"), QuantityKind::flag);
  EXPECT_EQ(viz::quantity_kind("Curvedness_s2"), QuantityKind::magnitude);
  EXPECT_EQ(viz::quantity_kind("LBE_r0.3"), QuantityKind::other);
  const viz::QuantityName n = viz::split_quantity_name("H_ii_r2%");
  EXPECT_EQ(n.base, "H_ii");
  EXPECT_EQ(n.radius, "2%");
  EXPECT_EQ(viz::split_quantity_name("SI_ii").base, "SI_ii");
  EXPECT_EQ(viz::quantity_label("H_s2"), "H (scale 2)");
  EXPECT_EQ(viz::quantity_label("H_ii_r0.3"), "H_ii (r = 0.3)");
  EXPECT_EQ(viz::quantity_description("H_s2"), "mean curvature H (scale 2)");
  EXPECT_EQ(viz::quantity_description("H_ii_r0.3"),
            "H_ii (integral-invariant mean curvature, r = 0.3)");
  EXPECT_EQ(viz::quantity_unit("K_ii", "mm"), "1/mm\u00b2");
  EXPECT_EQ(viz::quantity_unit("H_s2", "mm"), "1/mm");
  EXPECT_EQ(viz::quantity_unit("LBE_r4", "mm"), "1/mm\u00b2");
  EXPECT_EQ(viz::quantity_unit("NSV", "mm"), "");
  EXPECT_EQ(viz::resolve_color_map("auto", "H_ii_r0.3"), "diverging");
  EXPECT_EQ(viz::resolve_color_map("auto", "SI_ii"), "diverging");
  EXPECT_EQ(viz::resolve_color_map("auto", "LBE"), "viridis");
}

TEST(VizQuantity, ExtraArraysAreListedResolvedAndUnknownNamesListThem) {
  auto torus = test::torus(16, 8);
  const std::size_t n = torus.field.size();
  std::vector<float> lbe(n), h2(n);
  for (std::size_t i = 0; i < n; ++i) {
    lbe[i] = 3.f + float(i) / float(n);  // [3, 4)
    h2[i] = 0.5f * torus.field.H[i];
  }
  torus.field.extra.push_back({"LBE_r0.3", lbe});
  torus.field.extra.push_back({"H_s2", h2});
  const auto names = viz::field_quantities(torus.field);
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(names[names.size() - 2], "LBE_r0.3");
  EXPECT_EQ(names.back(), "H_s2");
  EXPECT_EQ(names.front(), "H");
  EXPECT_EQ(viz::resolve_quantity(torus.field, "lbe_r0.3"), "LBE_r0.3") << "any letter case";
  EXPECT_EQ(viz::quantity_values(torus.field, "LBE_r0.3"), lbe);
  try {
    viz::quantity_values(torus.field, "H_ii");
    ADD_FAILURE() << "no H_ii on this field";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'H_ii'"), std::string::npos) << m;
    EXPECT_NE(m.find("LBE_r0.3"), std::string::npos) << m;
    EXPECT_NE(m.find("H_s2"), std::string::npos) << m;
    EXPECT_NE(m.find("Curvedness"), std::string::npos) << m;
  }
  // an arbitrary array: its percentile range, not zero-based, not symmetric
  const viz::ColorRange r = viz::color_range(lbe, "LBE_r0.3", 2);
  EXPECT_NEAR(r.lo, 3.02, 2e-3);
  EXPECT_NEAR(r.hi, 3.98, 2e-3);
  const viz::ColorRange r0 = viz::color_range(lbe, "LBE_r0.3", 0);
  EXPECT_FLOAT_EQ(float(r0.lo), lbe.front());
  EXPECT_FLOAT_EQ(float(r0.hi), lbe.back());
  // a constant array still gets a range around its value
  const viz::ColorRange c = viz::color_range(std::vector<float>(10, 7.f), "Vr", 2);
  EXPECT_LT(c.lo, 7.0);
  EXPECT_GT(c.hi, 7.0);
  EXPECT_NEAR(c.hi - c.lo, 0.014, 1e-9);
}

TEST(VizQuantity, SuffixedCurvatureIsDivergingWithItsNeutralAtZero) {
  std::vector<float> v;
  for (int i = 0; i < 1000; ++i) v.push_back(-0.2f + 0.8f * float(i) / 999.f);  // [-0.2, 0.6]
  const viz::ColorRange r = viz::color_range(v, "H_s2", 2);
  EXPECT_DOUBLE_EQ(r.lo, -r.hi) << "symmetric about zero, as H";
  EXPECT_NEAR(r.hi, 0.584, 0.01);
  const std::string cmap = viz::resolve_color_map("auto", "H_s2");
  ASSERT_EQ(cmap, "diverging");
  auto map = viz::make_color_map(r, cmap);
  double zero[3], neutral[3] = {0xf7 / 255., 0xf7 / 255., 0xf7 / 255.};
  map->GetColor(0.0, zero);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(zero[c], neutral[c], 1e-6) << c;
  // one-signed: zero to the extreme, as for H
  std::vector<float> pos(v.begin() + 300, v.end());
  for (float& x : pos) x = std::fabs(x) + 0.01f;
  const viz::ColorRange p = viz::color_range(pos, "K_ii_r4", 2);
  EXPECT_EQ(p.lo, 0.0);
  EXPECT_GT(p.hi, 0.5);
  EXPECT_EQ(viz::color_range(v, "SI_ii", 2).lo, -1.0);
  EXPECT_EQ(viz::color_range(v, "Unreliable_s2", 2).hi, 1.0);
}

TEST(VizLegend, TickLabelsOfANearConstantArrayReadApart) {
  const double lo = 0.52359, hi = 0.52361;
  std::vector<std::string> labels;
  for (int i = 0; i < 5; ++i) labels.push_back(viz::tick_label(lo + (hi - lo) * i / 4, hi - lo));
  for (int i = 1; i < 5; ++i) EXPECT_NE(labels[i], labels[i - 1]) << labels[i];
  EXPECT_EQ(labels.front(), "0.52359");
  EXPECT_EQ(viz::tick_label(0.25, 1.0), "0.25") << "ordinary ranges keep %.3g";
  EXPECT_EQ(viz::tick_label(-0.123456, 1.0), "-0.123");
  EXPECT_EQ(viz::tick_label(1e-12, 1.0), "0");
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
  EXPECT_NE(viz::kDir1Color[0], viz::kDir2Color[0]) << "two contrasting colours";
  ASSERT_NE(glyphs->GetCellData()->GetArray("Halo"), nullptr);
  ASSERT_NE(glyphs->GetCellData()->GetArray("Direction"), nullptr);
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

TEST(VizDirectionGlyphs, CountAndLengthFollowTheOptions) {
  const auto t = test::torus(1.f, 0.4f, 192, 96);
  auto sites = [&](int count) {
    viz::GlyphOptions g;
    g.count = count;
    return viz::direction_glyphs(t.mesh, t.field, g)->GetNumberOfLines() / 2;
  };
  const vtkIdType few = sites(60), more = sites(400);
  EXPECT_GT(few, 20);
  EXPECT_LT(few, 180);
  EXPECT_GT(more, 3 * few) << "more glyphs asked for";
  EXPECT_LT(more, 1200);
  // never denser than 2.5 mean edges, however many are asked for
  EXPECT_LT(sites(10000000), static_cast<vtkIdType>(t.mesh.vertex_count() / 4));
  // the default grows with the image
  viz::GlyphOptions small, large;
  small.image_width = small.image_height = 300;
  large.image_width = 1920, large.image_height = 1080;
  EXPECT_LT(viz::direction_glyphs(t.mesh, t.field, small)->GetNumberOfLines(),
            viz::direction_glyphs(t.mesh, t.field, large)->GetNumberOfLines());
  viz::GlyphOptions fixed;
  fixed.length = 0.05;
  auto g = viz::direction_glyphs(t.mesh, t.field, fixed);
  double a[3], b[3];
  g->GetPoint(0, a);
  g->GetPoint(1, b);
  EXPECT_NEAR(std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2])),
              0.05, 1e-6);
}
