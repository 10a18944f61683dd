// The per-vertex scale choice (curvature/adaptive_scale.h) on synthetic pilots: where the two
// pilots agree (no bias, as on a sphere) every vertex takes the largest scale its noise allows;
// where they differ by far more than the noise (a strong bias) it takes a small one; a shape's
// curvature caps the scale; and the choice does not depend on the vertices' order.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "core/error.h"
#include "curvature/adaptive_scale.h"

using namespace isocurv;
using namespace isocurv::curvature;

namespace {

struct Pilots {
  Positions positions;
  std::vector<float> H1, g1, H2, g2, kappa;
  ScalePilots at(double s1, double s2) const { return {s1, s2, &H1, &g1, &H2, &g2, &kappa}; }
};

// A 40 x 40 patch of vertices half a voxel apart, H 0.05 at the first pilot, `bias` added at the
// second, noise of deviation `noise` (value units) on unit voxels, gradient 50 at both pilots.
Pilots patch(double bias, double kappa = 0.0) {
  Pilots p;
  std::mt19937 rng(3);
  std::normal_distribution<float> jitter(0.0f, 1e-4f);
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      p.positions.push_back({0.5f * x, 0.5f * y, 0.0f});
      p.H1.push_back(0.05f + jitter(rng));
      p.H2.push_back(float(0.05 + bias) + jitter(rng));
      p.g1.push_back(50.0f), p.g2.push_back(50.0f);
      p.kappa.push_back(float(kappa));
    }
  return p;
}

NoiseModel model() {
  NoiseModel m;
  m.noise = 3;
  m.cell_volume = 1;
  return m;
}

TEST(AdaptiveScale, AgreeingPilotsGiveTheLargestScale) {
  const Pilots p = patch(0.0);
  const std::vector<float> s = choose_vertex_scales(p.positions, model(), p.at(2, 4), 0.8, 12);
  for (float v : s) EXPECT_NEAR(v, 12.0, 12.0 * 0.2) << "no bias: the noise alone decides";
}

TEST(AdaptiveScale, AStrongBiasGivesASmallScale) {
  const Pilots p = patch(0.01);  // H moves by 0.01 from scale 2 to 4: L = 0.01 / 6
  const std::vector<float> s = choose_vertex_scales(p.positions, model(), p.at(2, 4), 0.8, 12);
  // The optimum of N(s)^2 + (s^2 L / 2)^2 with N(s) = 0.106 * 3 / (50 s^3.5): s about 1.2.
  for (float v : s) {
    EXPECT_GE(v, 0.8f);
    EXPECT_LT(v, 2.0f);
  }
}

TEST(AdaptiveScale, TheShapeCapsTheScale) {
  const Pilots p = patch(0.0, /*kappa=*/0.25);
  const std::vector<float> s = choose_vertex_scales(p.positions, model(), p.at(2, 4), 0.8, 12);
  for (float v : s) EXPECT_LE(v, kShapeScale / 0.25 + 1e-4);
}

TEST(AdaptiveScale, TheVertexOrderDoesNotMatter) {
  const Pilots p = patch(0.002);
  const std::vector<float> s = choose_vertex_scales(p.positions, model(), p.at(2, 4), 0.8, 12);
  std::vector<std::size_t> order(p.positions.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  Pilots q;
  for (std::size_t i : order) {
    q.positions.push_back(p.positions[i]);
    q.H1.push_back(p.H1[i]), q.H2.push_back(p.H2[i]);
    q.g1.push_back(p.g1[i]), q.g2.push_back(p.g2[i]), q.kappa.push_back(p.kappa[i]);
  }
  const std::vector<float> t = choose_vertex_scales(q.positions, model(), q.at(2, 4), 0.8, 12);
  for (std::size_t j = 0; j < order.size(); ++j) EXPECT_EQ(t[j], s[order[j]]) << j;
}

TEST(AdaptiveScale, BadInputIsAnError) {
  const Pilots p = patch(0.0);
  EXPECT_THROW(choose_vertex_scales(p.positions, model(), p.at(4, 2), 0.8, 12), Error);
  Pilots short_one = p;
  short_one.H2.pop_back();
  EXPECT_THROW(choose_vertex_scales(p.positions, model(), short_one.at(2, 4), 0.8, 12), Error);
}

}  // namespace
