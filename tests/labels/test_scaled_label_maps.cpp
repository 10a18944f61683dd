// Issue 55, 4.1: a NIfTI label map whose scl_slope / scl_inter make its integers non-integer.
// The loader applies the scaling (the values are real values); --labels (label_map_labels) then
// refuses the map with one line naming scl_slope/scl_inter, where slope 0.5 once merged labels 1
// and 2 (0.5 and 1 both rounded to 1) and inter 0.25 gave a "fills the box" warning for every
// label followed by a second error line. A scaling that keeps the values integers is a label map.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "labels/label_map.h"
#include "tests/volume/test_files.h"
#include "volume/from_dense.h"
#include "volume/load.h"

namespace isocurv::labels {
namespace scaled_nifti {

/// An 8^3 int16 NIfTI label map (label 1 on x < 4, label 2 on x >= 4 with y >= 4, else 0) with
/// the given scl_slope and scl_inter, written to `path`.
void write_labels(const std::string& path, float slope, float inter) {
  std::vector<std::uint8_t> h(352, 0);
  auto put = [&](std::size_t off, auto value) { std::memcpy(&h[off], &value, sizeof(value)); };
  put(0, std::int32_t(348));
  put(40, std::int16_t(3));
  for (std::size_t i = 1; i <= 3; ++i) put(40 + 2 * i, std::int16_t(8));
  for (std::size_t i = 4; i < 8; ++i) put(40 + 2 * i, std::int16_t(1));
  put(70, std::int16_t(4));  // int16
  put(72, std::int16_t(16));
  for (std::size_t i = 0; i < 4; ++i) put(76 + 4 * i, 1.0f);
  put(108, 352.0f);
  put(112, slope);
  put(116, inter);
  std::memcpy(&h[344], "n+1", 4);
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const std::int16_t v = x < 4 ? 1 : y >= 4 ? 2 : 0;
        const std::size_t at = h.size();
        h.resize(at + 2);
        std::memcpy(&h[at], &v, 2);
      }
  voltest::write_file(path, h);
}

}  // namespace scaled_nifti

TEST(LabelMapScaled, NiftiScalingToNonIntegersIsRefusedNamingIt) {
  voltest::TempDir dir;
  for (const auto& [slope, inter] : std::vector<std::pair<float, float>>{{0.5f, 0}, {1, 0.25f}, {1.5f, 0}}) {
    const std::string path = dir.file("labels.nii");
    scaled_nifti::write_labels(path, slope, inter);
    const volume::Volume v = volume::load(path);
    try {
      label_map_labels(v);
      ADD_FAILURE() << "slope " << slope << " inter " << inter << ": accepted as a label map";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("scl_slope/scl_inter"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(LabelMapScaled, NiftiScalingThatKeepsIntegersGivesTheScaledLabels) {
  voltest::TempDir dir;
  const std::string path = dir.file("labels.nii");
  scaled_nifti::write_labels(path, 2, 10);  // 0 1 2 -> 10 12 14
  const auto labels = label_map_labels(volume::load(path));
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].value, 10);
  EXPECT_EQ(labels[1].value, 12);
  EXPECT_EQ(labels[1].voxels, 4u * 8 * 8);
  EXPECT_EQ(labels[2].value, 14);
  EXPECT_EQ(labels[2].voxels, 4u * 4 * 8);
}

// Integer voxel types whose values are not integers can only come from such a scaling, but the
// check does not depend on the format: any integer-typed volume holding 2.5 is refused.
TEST(LabelMapScaled, NonIntegerValuesOfAnIntegerTypeAreRefused) {
  std::vector<float> data(27, 0.f);
  data[13] = 2.5f;
  auto xform = openvdb::math::Transform::createLinearTransform(1.0);
  const volume::Volume v =
      volume::from_dense(data.data(), {3, 3, 3}, xform, {"odd.nrrd", "nrrd", "uint8", "", volume::Inside::Above});
  try {
    label_map_labels(v);
    ADD_FAILURE() << "2.5 accepted as a label";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2.5"), std::string::npos) << e.what();
  }
}

}  // namespace isocurv::labels
