// labels::for_each_label_surface, label_surfaces and scale_margin (labels/label_surfaces.h): each
// label's surface is its own indicator's surface alone, in the picked order, with the curvature
// the callable gives; labels that fill the map are left out and named; the merge keeps the parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "labels/label_map.h"
#include "labels/label_surfaces.h"
#include "mc/extract_reference.h"
#include "volume/from_dense.h"

namespace isocurv::labels {
namespace label_surfaces_test {

/// An n^3 uint8 label map (spacing `spacing`) whose voxel (x, y, z) holds f(x, y, z).
template <class F>
volume::Volume surfaces_map(int n, double spacing, F f) {
  std::vector<float> data(static_cast<std::size_t>(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) data[(static_cast<std::size_t>(z) * n + y) * n + x] = f(x, y, z);
  auto xform = openvdb::math::Transform::createLinearTransform(spacing);
  return volume::from_dense(data.data(), {n, n, n}, xform,
                            {"labels.nrrd", "nrrd", "uint8", "", volume::Inside::Above});
}

/// Two touching balls of radius 6 voxels in a 30^3 map of spacing 0.5: label 4 centred at voxel
/// x = 10, label 9 at x = 16 (it takes the voxels that are not 4's), and a one-voxel label 2 in a
/// corner.
volume::Volume two_balls() {
  return surfaces_map(30, 0.5, [](int x, int y, int z) {
    auto in = [&](int cx) { return (x - cx) * (x - cx) + (y - 15) * (y - 15) + (z - 15) * (z - 15) < 36; };
    if (x == 2 && y == 2 && z == 2) return 2.f;
    return in(10) ? 4.f : in(16) ? 9.f : 0.f;
  });
}

LabelSurfaceSteps reference_steps(int margin) {
  LabelSurfaceSteps steps;
  steps.margin = margin;
  steps.extract = [](const volume::Volume& v, float iso) { return mc::extract_reference(v, iso); };
  return steps;
}

/// A made-up field for `mesh`: H holds the indicator's label (from its grid name) plus the
/// vertex's index / 1000, so that a merged field's slices say where they came from.
curvature::CurvatureField tagged_field(const Mesh& mesh, const volume::Volume& indicator) {
  const float label = std::stof(indicator.grid_name.substr(std::string("label ").size()));
  curvature::CurvatureField f;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) f.H.push_back(label + float(i) / 1000);
  return f;
}

TEST(LabelSurfaces, EachLabelIsItsIndicatorsSurfaceAloneInThePickedOrder) {
  const volume::Volume map = two_balls();
  const std::vector<Label> all = label_map_labels(map);
  std::vector<std::int64_t> missing;
  const std::vector<Label> picked = pick_labels(all, {9, 2, 4}, missing);
  ASSERT_EQ(picked.size(), 3u);
  const int margin = scale_margin(map);
  std::vector<std::int64_t> seen;
  const auto empty = for_each_label_surface(map, picked, reference_steps(margin), [&](LabelSurface& s) {
    seen.push_back(s.label.value);
    EXPECT_EQ(s.isovalue, 0.5f);
    EXPECT_FALSE(s.field.has_value());  // no curvature callable
    const volume::Volume alone = label_indicator(map, s.label, margin);
    EXPECT_EQ(s.indicator.domain, alone.domain);
    const Mesh expected = mc::extract_reference(alone, 0.5f);
    ASSERT_EQ(s.mesh.positions.size(), expected.positions.size()) << s.label.value;
    EXPECT_EQ(s.mesh.positions, expected.positions);
    EXPECT_EQ(s.mesh.triangles, expected.triangles);
    // Its own surface: not the map's at 0.5, which would wrap the touching balls together.
    float xmax = -1e9f;
    for (const Vec3f& p : s.mesh.positions) xmax = std::max(xmax, p[0]);
    if (s.label.value == 4) EXPECT_LT(xmax, 8.f);  // ball 4 ends at voxel x 15.5, world 7.75
    if (s.label.value == 9) EXPECT_GT(xmax, 10.f);  // ball 9 ends at voxel x 21.5
  });
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(seen, (std::vector<std::int64_t>{9, 2, 4}));
}

TEST(LabelSurfaces, MergesThePartsWithTheirLabelsAndCurvature) {
  const volume::Volume map = two_balls();
  std::vector<std::int64_t> missing;
  const std::vector<Label> picked = pick_labels(label_map_labels(map), {4, 9}, missing);
  LabelSurfaceSteps steps = reference_steps(scale_margin(map));
  int curvature_calls = 0;
  steps.curvature = [&](const Mesh& mesh, const volume::Volume& indicator, float iso) {
    ++curvature_calls;
    EXPECT_EQ(iso, 0.5f);
    EXPECT_EQ(indicator.voxel_type, "uint8");  // the indicator, not the map
    return tagged_field(mesh, indicator);
  };
  const LabelSurfaces made = label_surfaces(map, picked, steps);
  EXPECT_EQ(curvature_calls, 2);
  EXPECT_TRUE(made.empty.empty());
  const LabelledMesh& m = made.merged;
  ASSERT_EQ(m.parts.size(), 2u);
  std::size_t vertices = 0, triangles = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const LabelPart& p = m.parts[k];
    EXPECT_EQ(p.value, picked[k].value);
    const Mesh alone = mc::extract_reference(label_indicator(map, picked[k], scale_margin(map)), 0.5f);
    EXPECT_EQ(p.vertices, alone.positions.size());
    EXPECT_EQ(p.triangles, alone.triangles.size());
    EXPECT_EQ(p.first_vertex, vertices);
    EXPECT_EQ(p.first_triangle, triangles);
    vertices += p.vertices;
    triangles += p.triangles;
    Mesh mesh;
    curvature::CurvatureField field;
    extract_label(m, p.value, mesh, field);
    EXPECT_EQ(mesh.positions, alone.positions);
    EXPECT_EQ(mesh.triangles, alone.triangles);
    ASSERT_EQ(field.H.size(), alone.positions.size());
    EXPECT_EQ(field.H.back(), float(p.value) + float(p.vertices - 1) / 1000);
    for (std::size_t t = p.first_triangle; t < p.first_triangle + p.triangles; ++t)
      ASSERT_EQ(m.triangle_labels[t], p.value);
  }
  EXPECT_EQ(m.mesh.positions.size(), vertices);
  EXPECT_EQ(m.triangle_labels.size(), triangles);
  ASSERT_EQ(m.field.extra.size(), 1u);
  EXPECT_EQ(m.field.extra[0].name, "Label");
  EXPECT_EQ(m.field.extra[0].values.front(), 4.f);
  EXPECT_EQ(m.field.extra[0].values.back(), 9.f);
}

TEST(LabelSurfaces, ALabelThatFillsTheMapIsNamedAndNeitherEstimatedNorVisited) {
  const volume::Volume full = surfaces_map(8, 1.0, [](int, int, int) { return 5.f; });
  const std::vector<Label> picked = label_map_labels(full);
  LabelSurfaceSteps steps = reference_steps(2);
  steps.curvature = [](const Mesh&, const volume::Volume&, float) -> curvature::CurvatureField {
    ADD_FAILURE() << "curvature of an empty surface";
    return {};
  };
  int visits = 0;
  const auto empty = for_each_label_surface(full, picked, steps, [&](LabelSurface&) { ++visits; });
  EXPECT_EQ(visits, 0);
  EXPECT_EQ(empty, (std::vector<std::int64_t>{5}));
  const LabelSurfaces made = label_surfaces(full, picked, steps);
  EXPECT_TRUE(made.merged.parts.empty());
  EXPECT_TRUE(made.merged.mesh.positions.empty());
  EXPECT_EQ(made.empty, (std::vector<std::int64_t>{5}));
}

TEST(LabelSurfaces, StagesAreReportedAndTheVisitorsErrorStopsTheLoop) {
  const volume::Volume map = two_balls();
  std::vector<std::int64_t> missing;
  const std::vector<Label> picked = pick_labels(label_map_labels(map), {4, 9}, missing);
  LabelSurfaceSteps steps = reference_steps(scale_margin(map));
  std::vector<std::string> stages;
  steps.stage = [&](const std::string& s) { stages.push_back(s); };
  label_surfaces(map, {picked[0]}, steps);
  EXPECT_EQ(stages, (std::vector<std::string>{"labels", "extract", "", "labels", ""}));
  int visits = 0;
  EXPECT_THROW(for_each_label_surface(map, picked, steps,
                                      [&](LabelSurface&) {
                                        ++visits;
                                        throw Error("stop");
                                      }),
               Error);
  EXPECT_EQ(visits, 1);
  LabelSurfaceSteps none;
  EXPECT_THROW(for_each_label_surface(map, picked, none, [](LabelSurface&) {}), Error);
  steps.margin = 0;
  EXPECT_THROW(label_surfaces(map, picked, steps), Error);
}

TEST(LabelSurfaces, TheMarginFollowsTheLargestScaleInVoxelsOfTheSmallestSpacing) {
  const volume::Volume map = two_balls();  // spacing 0.5
  EXPECT_EQ(scale_margin(map), indicator_margin(2.0));  // the binary scale: 2 + 4 * 2
  EXPECT_EQ(scale_margin(map), 10);
  EXPECT_EQ(scale_margin(map, {0}), 10);        // auto
  EXPECT_EQ(scale_margin(map, {0.5}), 10);      // 1 voxel: below the binary scale
  EXPECT_EQ(scale_margin(map, {3, 1}), 2 + 24);  // 6 voxels
  EXPECT_EQ(scale_margin(map, {1000}), 2 + 4 * 64);  // capped at 64 deviations
}

}  // namespace label_surfaces_test
}  // namespace isocurv::labels
