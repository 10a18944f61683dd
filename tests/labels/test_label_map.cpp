// labels::label_map_labels, pick_labels, parse_label_list, label_indicator and the merge of the
// labels' surfaces (append_label / extract_label).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "labels/label_map.h"
#include "labels/label_merge.h"
#include "volume/from_dense.h"

namespace isocurv::labels {
namespace {

/// A dims^3 label map of `type` whose voxel (x, y, z) holds f(x, y, z).
template <class F>
volume::Volume label_map(int n, const std::string& type, F f) {
  std::vector<float> data(static_cast<std::size_t>(n) * n * n);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) data[(static_cast<std::size_t>(z) * n + y) * n + x] = f(x, y, z);
  auto xform = openvdb::math::Transform::createLinearTransform(0.5);
  return volume::from_dense(data.data(), {n, n, n}, xform, {"labels.nrrd", "nrrd", type, "", volume::Inside::Above});
}

/// Two boxes: label 3 on x in [2, 9], label 7 on x in [10, 14] (touching), y, z in [4, 11].
volume::Volume two_boxes() {
  return label_map(20, "uint8", [](int x, int y, int z) {
    if (y < 4 || y > 11 || z < 4 || z > 11) return 0.f;
    return x >= 2 && x <= 9 ? 3.f : x >= 10 && x <= 14 ? 7.f : 0.f;
  });
}

TEST(LabelMap, ListsEachNonZeroValueWithItsVoxelsAndBox) {
  const auto labels = label_map_labels(two_boxes());
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].value, 3);
  EXPECT_EQ(labels[0].voxels, 8u * 8 * 8);
  EXPECT_EQ(labels[0].box, openvdb::CoordBBox(openvdb::Coord(2, 4, 4), openvdb::Coord(9, 11, 11)));
  EXPECT_EQ(labels[1].value, 7);
  EXPECT_EQ(labels[1].voxels, 5u * 8 * 8);
  EXPECT_EQ(labels[1].box, openvdb::CoordBBox(openvdb::Coord(10, 4, 4), openvdb::Coord(14, 11, 11)));
}

TEST(LabelMap, RefusesFloatVolumesAndTooManyLabels) {
  const auto floats = label_map(8, "float", [](int x, int, int) { return float(x); });
  EXPECT_THROW(label_map_labels(floats), Error);
  // 41^3 = 68,921 distinct values: more than kMaxLabels.
  const auto many = label_map(41, "int32", [](int x, int y, int z) { return float(1 + x + 41 * (y + 41 * z)); });
  try {
    label_map_labels(many);
    FAIL() << "more than 65,535 labels accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("65535"), std::string::npos) << e.what();
  }
  // Exactly kMaxLabels + 0 is fine: values 1..(40^3 = 64,000).
  const auto fine = label_map(40, "uint16", [](int x, int y, int z) { return float(1 + x + 40 * (y + 40 * z)); });
  EXPECT_EQ(label_map_labels(fine).size(), 64000u);
}

// A file's label 2^24 + 1 arrives in the volume's floats as 2^24: it must be refused, not merged
// with a true 2^24 (the fuzzing campaign's finding); 2^24 - 1 is exact and kept.
TEST(LabelMap, LabelsThatFloatsRoundAreRefused) {
  for (const double v : {16777217.0, -16777217.0, 16777216.0}) {
    const auto map = label_map(8, "int32", [v](int x, int, int) { return x < 4 ? 5.f : float(v); });
    EXPECT_THROW(label_map_labels(map), Error) << v;
  }
  const auto exact = label_map(8, "int32", [](int x, int, int) { return x < 4 ? 5.f : 16777215.f; });
  const auto labels = label_map_labels(exact);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[1].value, 16777215);
}

TEST(LabelMap, PicksAndParsesLabelLists) {
  EXPECT_EQ(parse_label_list("3,7"), (std::vector<std::int64_t>{3, 7}));
  EXPECT_EQ(parse_label_list(" 7 , -2"), (std::vector<std::int64_t>{7, -2}));
  EXPECT_THROW(parse_label_list("3,,7"), Error);
  EXPECT_THROW(parse_label_list("3,x"), Error);
  EXPECT_THROW(parse_label_list("3,3"), Error);
  EXPECT_THROW(parse_label_list("2.5"), Error);
  const auto all = label_map_labels(two_boxes());
  std::vector<std::int64_t> missing;
  const auto picked = pick_labels(all, {7, 9}, missing);
  ASSERT_EQ(picked.size(), 1u);
  EXPECT_EQ(picked[0].value, 7);
  EXPECT_EQ(missing, (std::vector<std::int64_t>{9}));
}

TEST(LabelMap, IndicatorIsOneOnTheLabelInTheMapsIndexSpace) {
  const volume::Volume map = two_boxes();
  const auto all = label_map_labels(map);
  const volume::Volume ind = label_indicator(map, all[1], 2);
  EXPECT_EQ(ind.domain, openvdb::CoordBBox(openvdb::Coord(8, 2, 2), openvdb::Coord(16, 13, 13)));
  EXPECT_EQ(ind.voxel_type, "uint8");
  EXPECT_DOUBLE_EQ(ind.stats.min, 0);
  EXPECT_DOUBLE_EQ(ind.stats.max, 1);
  EXPECT_EQ(ind.spacing(), map.spacing());
  auto a = ind.grid->getConstAccessor();
  auto m = map.grid->getConstAccessor();
  std::size_t ones = 0;
  for (auto it = ind.domain.begin(); it; ++it) {
    const float want = m.getValue(*it) == 7.f ? 1.f : 0.f;
    ASSERT_EQ(a.getValue(*it), want) << *it;
    ones += want == 1.f;
  }
  EXPECT_EQ(ones, all[1].voxels);
  // The grown box is clipped to the map's domain.
  const volume::Volume wide = label_indicator(map, all[0], 5);
  EXPECT_EQ(wide.domain.min(), openvdb::Coord(0, 0, 0));
}

TEST(LabelMerge, ConcatenatesSurfacesAndSlicesThemBack) {
  Mesh a, b;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.triangles = {{0, 1, 2}};
  b.positions = {{5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {6, 1, 0}};
  b.triangles = {{0, 1, 2}, {1, 3, 2}};
  curvature::CurvatureField fa, fb;
  fa.H = {1, 2, 3};
  fa.K = {4, 5, 6};
  fb.H = {7, 8, 9, 10};  // no K: the merged field has none
  LabelledMesh m;
  append_label(m, 3, a, &fa);
  append_label(m, 7, b, &fb);
  ASSERT_EQ(m.mesh.positions.size(), 7u);
  EXPECT_EQ(m.mesh.triangles[2], (Tri{4, 6, 5}));
  EXPECT_EQ(m.triangle_labels, (std::vector<std::int32_t>{3, 7, 7}));
  EXPECT_EQ(m.field.H, (std::vector<float>{1, 2, 3, 7, 8, 9, 10}));
  EXPECT_TRUE(m.field.K.empty());
  ASSERT_EQ(m.field.extra.size(), 1u);
  EXPECT_EQ(m.field.extra[0].name, "Label");
  EXPECT_EQ(m.field.extra[0].values, (std::vector<float>{3, 3, 3, 7, 7, 7, 7}));

  Mesh back;
  curvature::CurvatureField field;
  extract_label(m, 7, back, field);
  EXPECT_EQ(back.positions, b.positions);
  EXPECT_EQ(back.triangles, b.triangles);
  EXPECT_EQ(field.H, fb.H);
  extract_label(m, 42, back, field);
  EXPECT_TRUE(back.positions.empty());
}

}  // namespace
}  // namespace isocurv::labels
