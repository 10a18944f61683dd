// summary_json / summary_text contents.
#include <gtest/gtest.h>

#include "volume/from_dense.h"
#include "volume/summary.h"

using namespace isocurv::volume;

TEST(VolumeSummary, JsonAndTextCarryTheFacts) {
  std::vector<float> data(1000);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = float(i % 100);
  auto xf = openvdb::math::Transform::createLinearTransform(0.5);
  const Volume v = from_dense(data.data(), {10, 10, 10}, xf, {"ten.raw", "raw", "uint8", "", Inside::Above});
  const auto j = summary_json(v);
  EXPECT_EQ(j["path"], "ten.raw");
  EXPECT_EQ(j["format"], "raw");
  EXPECT_EQ(j["voxel_type"], "uint8");
  EXPECT_EQ(j["dims"], nlohmann::json({10, 10, 10}));
  EXPECT_EQ(j["spacing"][0], 0.5);
  EXPECT_EQ(j["inside"], "above");
  EXPECT_EQ(j["min"], 0.0);
  EXPECT_EQ(j["max"], 99.0);
  EXPECT_NEAR(j["mean"].get<double>(), 49.5, 1e-9);
  EXPECT_EQ(j["nan_count"], 0);
  EXPECT_NEAR(j["percentiles"]["p50"].get<double>(), 49.5, 1.0);
  EXPECT_NEAR(j["percentiles"]["p1"].get<double>(), 1.0, 1.0);
  EXPECT_NEAR(j["percentiles"]["p99"].get<double>(), 98.0, 1.0);
  ASSERT_EQ(j["histogram16"].size(), 16u);
  std::uint64_t total = 0;
  for (const auto& c : j["histogram16"]) total += c.get<std::uint64_t>();
  EXPECT_EQ(total, 1000u);
  EXPECT_TRUE(j.contains("suggested_isovalue"));

  const std::string text = summary_text(v);
  for (const char* needle : {"ten.raw", "raw", "10 x 10 x 10", "0.5 0.5 0.5", "0 .. 99", "above", "Otsu"})
    EXPECT_NE(text.find(needle), std::string::npos) << needle << "\n" << text;
}
