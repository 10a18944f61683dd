// summary_json / summary_text contents.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "volume/from_dense.h"
#include "volume/load.h"
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
  // Integer data: exact values the volume holds. Each of 0..99 is 1% of the voxels, so the
  // smallest value with at least 50% at or below it is 49 (1%: 0, 99%: 98).
  EXPECT_EQ(j["percentiles"]["p50"].get<double>(), 49.0);
  EXPECT_EQ(j["percentiles"]["p1"].get<double>(), 0.0);
  EXPECT_EQ(j["percentiles"]["p99"].get<double>(), 98.0);
  EXPECT_TRUE(j["percentiles_exact"].get<bool>());
  ASSERT_EQ(j["histogram16"].size(), 16u);
  std::uint64_t total = 0;
  for (const auto& c : j["histogram16"]) total += c.get<std::uint64_t>();
  EXPECT_EQ(total, 1000u);
  EXPECT_TRUE(j.contains("suggested_isovalue"));

  const std::string text = summary_text(v);
  for (const char* needle : {"ten.raw", "raw", "10 x 10 x 10", "0.5 0.5 0.5", "0 .. 99", "above", "Otsu",
                             "50%: 49 ", "histogram"})
    EXPECT_NE(text.find(needle), std::string::npos) << needle << "\n" << text;
  // The histogram as text: 16 rows, each with a bar and its count, the counts adding up.
  std::size_t rows = 0;
  std::uint64_t counted = 0;
  std::istringstream in(text);
  for (std::string row; std::getline(in, row);)
    if (row.find('#') != std::string::npos) {
      ++rows;
      counted += std::stoull(row.substr(row.find_last_of(' ') + 1));
    }
  EXPECT_EQ(rows, 16u) << text;
  EXPECT_EQ(counted, 1000u) << text;
}

TEST(VolumeSummary, WideIntegerRangesAreExactAndFloatsInterpolated) {
  // int16 CT-like values over 4,000 levels (more than the histogram's 256 bins): still exact.
  std::vector<float> ct(20 * 20 * 20);
  for (std::size_t i = 0; i < ct.size(); ++i) ct[i] = float(-1024 + int(i % 4000));
  auto xf = openvdb::math::Transform::createLinearTransform(1.0);
  const Volume v = from_dense(ct.data(), {20, 20, 20}, xf, {"ct.raw", "raw", "int16", "", Inside::Above});
  const auto j = summary_json(v);
  EXPECT_TRUE(j["percentiles_exact"].get<bool>());
  // 8000 voxels: 0..3999 twice. 50% (4000 voxels) at or below -1024 + 1999.
  EXPECT_EQ(j["percentiles"]["p50"].get<double>(), -1024.0 + 1999);
  EXPECT_EQ(j["percentiles"]["p1"].get<double>(), -1024.0 + 39);
  // Float data: interpolated, and said so.
  std::vector<float> f(1000);
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = 0.001f * float(i);
  const Volume fv = from_dense(f.data(), {10, 10, 10}, xf, {"f.raw", "raw", "float", "", Inside::Above});
  EXPECT_FALSE(summary_json(fv)["percentiles_exact"].get<bool>());
  EXPECT_NE(summary_text(fv).find("interpolated"), std::string::npos);
}

// An isovalue from the file's own metadata is said to be the file's, not Otsu's.
TEST(VolumeSummary, TheSuggestedIsovalueSaysWhereItCameFrom) {
  openvdb::initialize();
  auto grid = openvdb::FloatGrid::create(0.0f);
  auto acc = grid->getAccessor();
  for (int z = 0; z < 12; ++z)
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x) acc.setValue(openvdb::Coord(x, y, z), float(x * 10));
  grid->setName("density");
  const std::string path =
      (std::filesystem::temp_directory_path() / ("isocurv_summary_" + std::to_string(::getpid()) + ".vdb")).string();
  openvdb::io::File(path).write({grid});
  const Volume otsu = load(path);
  EXPECT_NE(summary_text(otsu).find("(Otsu)"), std::string::npos) << summary_text(otsu);
  EXPECT_EQ(summary_json(otsu)["suggested_from"], "Otsu");
  grid->insertMeta("isovalue", openvdb::FloatMetadata(42.5f));
  openvdb::io::File(path).write({grid});
  const Volume tagged = load(path);
  std::filesystem::remove(path);
  EXPECT_EQ(tagged.stats.suggested_isovalue, 42.5);
  const std::string text = summary_text(tagged);
  EXPECT_NE(text.find("42.5 (the file's isovalue)"), std::string::npos) << text;
  EXPECT_EQ(text.find("Otsu"), std::string::npos) << text;
}

// info says when a volume looks like a label map, and points to --labels; scans and masks do not.
TEST(VolumeSummary, ALabelMapIsNamedAsOne) {
  auto xf = openvdb::math::Transform::createLinearTransform(1.0);
  std::vector<float> map(20 * 20 * 20, 0.0f);
  for (int z = 0; z < 20; ++z)
    for (int y = 0; y < 20; ++y)
      for (int x = 0; x < 20; ++x)
        if (x >= 2 && x < 8 && y >= 2 && y < 18 && z >= 2 && z < 18)
          map[std::size_t((z * 20 + y) * 20 + x)] = x < 5 ? 1.0f : 2.0f;
        else if (x >= 12 && x < 16 && y >= 4 && y < 10 && z >= 4 && z < 10)
          map[std::size_t((z * 20 + y) * 20 + x)] = 7.0f;
  const Volume labels = from_dense(map.data(), {20, 20, 20}, xf, {"seg.raw", "raw", "uint8", "", Inside::Above});
  const auto j = summary_json(labels);
  EXPECT_TRUE(j["looks_like_label_map"].get<bool>());
  EXPECT_EQ(j["label_count"], 3);
  EXPECT_NE(summary_text(labels).find("label map?"), std::string::npos) << summary_text(labels);
  EXPECT_NE(summary_text(labels).find("--labels"), std::string::npos);

  // The same values as floats, a 0/1 mask, and a scan holding every value of its range: no hint.
  const Volume floats = from_dense(map.data(), {20, 20, 20}, xf, {"seg.raw", "raw", "float", "", Inside::Above});
  EXPECT_FALSE(summary_json(floats)["looks_like_label_map"].get<bool>());
  std::vector<float> mask(map);
  for (float& m : mask) m = m > 0 ? 1.0f : 0.0f;
  const Volume binary = from_dense(mask.data(), {20, 20, 20}, xf, {"mask.raw", "raw", "uint8", "", Inside::Above});
  EXPECT_FALSE(summary_json(binary)["looks_like_label_map"].get<bool>());
  std::vector<float> scan(20 * 20 * 20);
  for (std::size_t i = 0; i < scan.size(); ++i) scan[i] = i < 5000 ? 0.0f : float(i % 200);
  const Volume ct = from_dense(scan.data(), {20, 20, 20}, xf, {"ct.raw", "raw", "uint8", "", Inside::Above});
  EXPECT_FALSE(summary_json(ct)["looks_like_label_map"].get<bool>());
  EXPECT_EQ(summary_text(ct).find("label map?"), std::string::npos);
}
