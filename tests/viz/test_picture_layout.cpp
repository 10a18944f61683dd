// layout_picture: title, legend and surface boxes inside the image, apart, at 300x300 to 4k.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "viz/picture_layout.h"

using namespace isocurv;

namespace {

void expect_fits(const viz::PictureLayout& l, const std::string& what) {
  const viz::PixelBox image{0, 0, l.width, l.height};
  EXPECT_TRUE(image.contains(l.title.box)) << what << ": title";
  EXPECT_TRUE(image.contains(l.legend)) << what << ": legend";
  EXPECT_TRUE(l.legend.contains(l.legend_title.box)) << what;
  EXPECT_TRUE(l.legend.contains(l.bar)) << what;
  for (const auto& t : l.labels) {
    EXPECT_TRUE(image.contains(t.box)) << what << ": label " << t.text;
    EXPECT_TRUE(l.legend.contains(t.box)) << what;
  }
  EXPECT_FALSE(l.surface.overlaps(l.title.box)) << what;
  EXPECT_FALSE(l.surface.overlaps(l.legend)) << what;
  EXPECT_FALSE(l.title.box.overlaps(l.legend)) << what;
  EXPECT_GT(l.surface.x1 - l.surface.x0, l.width / 2)
      << what << ": the surface keeps most of the width";
  EXPECT_GT(l.surface.y1 - l.surface.y0, l.height / 2) << what;
  for (std::size_t i = 1; i < l.labels.size(); ++i)
    EXPECT_FALSE(l.labels[i].box.overlaps(l.labels[i - 1].box)) << what << ": labels overlap";
}

}  // namespace

TEST(VizPictureLayout, TextIsMeasured) {
  const viz::PixelBox a = viz::measure_text("H", 20), b = viz::measure_text("Curvedness", 20),
                      c = viz::measure_text("Curvedness", 40),
                      two = viz::measure_text("K\n1/mm", 20);
  EXPECT_GT(a.x1 - a.x0, 3);
  EXPECT_GT(b.x1 - b.x0, 3 * (a.x1 - a.x0));
  EXPECT_NEAR(double(c.x1 - c.x0) / (b.x1 - b.x0), 2.0, 0.25);
  EXPECT_GT(two.y1 - two.y0, 1.6 * (a.y1 - a.y0)) << "two lines";
  EXPECT_TRUE(viz::measure_text("", 20).empty());
}

TEST(VizPictureLayout, LegendAndTitleFitFrom300x300To4k) {
  const std::string long_title =
      "a_rather_long_volume_file_name_from_a_scanner_0001.nii.gz  |  k2 (smaller principal "
      "curvature)  |  "
      "iso 1234.5  |  Rusinkiewicz";
  for (auto [w, h] : {std::pair{300, 300}, std::pair{320, 240}, std::pair{1024, 768},
                      std::pair{3840, 2160}, std::pair{2160, 3840}}) {
    for (const auto& legend : {std::string("Curvedness\n1/length"), std::string("K\n1/mm\u00b2"),
                               std::string("ShapeIndex")}) {
      const std::string what = std::to_string(w) + "x" + std::to_string(h) + " " + legend;
      expect_fits(viz::layout_picture(w, h, long_title, legend, -0.000123456, 12345.678), what);
      expect_fits(viz::layout_picture(w, h, "torus.vdb", legend, -1, 1, h / 8), what + " reserved");
    }
  }
  // the long title was shortened at 300 px, and keeps its end (the quantity and estimator)
  const auto l = viz::layout_picture(300, 300, long_title, "H", -1, 1);
  EXPECT_LT(l.title.text.size(), long_title.size());
  EXPECT_EQ(l.title.text.substr(l.title.text.size() - 12), "Rusinkiewicz");
  // fonts grow with the picture
  EXPECT_GT(viz::layout_picture(3840, 2160, "t", "H", -1, 1).labels[0].font_px,
            2 * viz::layout_picture(640, 480, "t", "H", -1, 1).labels[0].font_px);
}

TEST(VizPictureLayout, TicksRunFromLoToHiWithZeroShownAsZero) {
  const auto l = viz::layout_picture(800, 600, "", "H", -0.3, 0.3);
  ASSERT_EQ(l.ticks.size(), 5u);
  EXPECT_DOUBLE_EQ(l.ticks.front(), -0.3);
  EXPECT_DOUBLE_EQ(l.ticks.back(), 0.3);
  EXPECT_EQ(l.labels[2].text, "0");
  EXPECT_LT(l.labels[0].box.y0, l.labels[4].box.y0) << "lo at the bottom";
  EXPECT_TRUE(l.title.text.empty());
  EXPECT_EQ(l.surface.y1, 600) << "without a title the surface reaches the top";
}

TEST(VizPictureLayout, NoDataEntrySitsUnderTheBarInsideTheLegend) {
  for (const auto& [w, h] : {std::pair{300, 300}, std::pair{640, 480}, std::pair{1024, 768}, std::pair{3840, 2160}}) {
    const std::string what = std::to_string(w) + "x" + std::to_string(h);
    const viz::PictureLayout plain = viz::layout_picture(w, h, "title", "H\n1/mm", -0.5, 0.5);
    EXPECT_TRUE(plain.no_data.empty()) << what;
    EXPECT_TRUE(plain.no_data_label.text.empty()) << what;
    const viz::PictureLayout l = viz::layout_picture(w, h, "title", "H\n1/mm", -0.5, 0.5, 0, true);
    expect_fits(l, what + " with no data");
    ASSERT_FALSE(l.no_data.empty()) << what;
    EXPECT_EQ(l.no_data_label.text, "no data") << what;
    EXPECT_TRUE(l.legend.contains(l.no_data)) << what;
    EXPECT_TRUE(l.legend.contains(l.no_data_label.box)) << what;
    EXPECT_TRUE((viz::PixelBox{0, 0, w, h}.contains(l.no_data_label.box))) << what;
    EXPECT_LE(l.no_data.y1, l.bar.y0) << what << ": the swatch is under the bar";
    for (const auto& t : l.labels) {
      EXPECT_FALSE(t.box.overlaps(l.no_data_label.box)) << what << ": tick " << t.text;
      EXPECT_FALSE(t.box.overlaps(l.no_data)) << what;
    }
    EXPECT_GE(l.no_data.y0, 0) << what;
  }
}

// A label map's legend lists its labels: every one that fits, then how many more.
TEST(VizPictureLayout, CategoriesAreListedAndTheRestCounted) {
  std::vector<double> few = {1, 2, 7}, many;
  for (int i = 0; i < 300; ++i) many.push_back(1000 + i);
  for (auto [w, h] : {std::pair{300, 300}, std::pair{1024, 768}, std::pair{3840, 2160}}) {
    const auto a = viz::layout_picture(w, h, "labels.nii", "Label", 0, 1, 0, true, &few);
    ASSERT_EQ(a.swatches.size(), 3u);
    ASSERT_EQ(a.labels.size(), 3u);
    EXPECT_EQ(a.labels[2].text, "7");
    EXPECT_FALSE(a.no_data.empty());
    const auto b = viz::layout_picture(w, h, "labels.nii", "Label", 0, 1, 0, false, &many);
    ASSERT_FALSE(b.labels.empty());
    EXPECT_EQ(b.labels.size(), b.swatches.size() + 1) << "a last line for the rest";
    EXPECT_EQ(b.labels.back().text, "+" + std::to_string(300 - b.swatches.size()) + " more");
    const viz::PixelBox image{0, 0, w, h};
    for (const viz::PlacedText& t : b.labels) EXPECT_TRUE(image.contains(t.box)) << t.text;
    for (std::size_t i = 1; i < b.labels.size(); ++i)
      EXPECT_FALSE(b.labels[i].box.overlaps(b.labels[i - 1].box)) << i;
    EXPECT_FALSE(b.surface.overlaps(b.legend));
  }
}
