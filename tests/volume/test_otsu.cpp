// Otsu's threshold on synthetic histograms.
#include <gtest/gtest.h>

#include <cmath>

#include "volume/otsu.h"

using isocurv::volume::otsu_threshold;

TEST(VolumeOtsu, BimodalGaussiansSplitBetweenModes) {
  // Two Gaussian humps centred on bins 60 and 190 with different weights.
  std::vector<std::uint64_t> h(256, 0);
  for (int i = 0; i < 256; ++i)
    h[std::size_t(i)] = std::uint64_t(3000 * std::exp(-0.5 * std::pow((i - 60) / 12.0, 2)) +
                                      1000 * std::exp(-0.5 * std::pow((i - 190) / 15.0, 2)));
  const double t = otsu_threshold(h, 0, 256);  // bin width 1: threshold is in bin units
  EXPECT_GT(t, 100);
  EXPECT_LT(t, 150);
}

TEST(VolumeOtsu, TwoLabelsGiveTheirMidpoint) {
  std::vector<std::uint64_t> h(256, 0);
  h[0] = 900;
  h[255] = 100;
  EXPECT_NEAR(otsu_threshold(h, 0, 255), 127.5, 1e-9);
  EXPECT_NEAR(otsu_threshold(h, 0, 1), 0.5, 1e-9);
}

TEST(VolumeOtsu, DegenerateHistograms) {
  std::vector<std::uint64_t> h(256, 0);
  EXPECT_EQ(otsu_threshold(h, 2, 5), 2);  // empty
  h[7] = 10;
  EXPECT_EQ(otsu_threshold(h, 2, 5), 2);  // one occupied bin
  EXPECT_EQ(otsu_threshold(h, 3, 3), 3);  // min == max
}
