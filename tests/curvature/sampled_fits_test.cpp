// quadric and sampling, the fits that sample normal curvatures, on what marching cubes leaves
// (issue 55): a fit whose sample directions nearly lie on two lines is refused (the vertex flagged
// Unreliable), a sample from a tiny raised edge is left out, and no vertex they measure has
// max(|k1|, |k2|) above 4 / mean edge. Before: up to 73 / mean edge, unflagged, on the
// marching-cubes torus 64^3 (docs/curvature.md, "On marching-cubes meshes").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh_measures.h"
#include "curvature/normal_sampling.h"
#include "curvature/quadric_fit.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;
using SampledFit = std::function<CurvatureField(const Mesh&, const curvature::Options&)>;

const std::vector<std::pair<std::string, SampledFit>>& sampled_fits() {
  static const std::vector<std::pair<std::string, SampledFit>> fits = {
      {"quadric",
       [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_quadric_fit_reference(m, o);
       }},
      {"sampling", [](const Mesh& m, const curvature::Options& o) {
         return curvature::estimate_normal_sampling_reference(m, o);
       }}};
  return fits;
}

double largest_curvature(const CurvatureField& f, std::size_t i) {
  return std::max(std::abs(f.k1[i]), std::abs(f.k2[i]));
}

// A fan around vertex 0 at the origin (normal +z) on the sphere of radius `radius` below it
// (z = -r^2 / 2R: k = +1/R), one neighbour per (angle in degrees, distance, extra height).
struct FanNeighbour {
  double degrees, distance, lift;
};
Mesh sphere_fan(const std::vector<FanNeighbour>& ring, double radius) {
  Mesh m;
  m.positions.push_back({0, 0, 0});
  for (const FanNeighbour& q : ring) {
    const double a = q.degrees * M_PI / 180, r = q.distance;
    m.positions.push_back({float(r * std::cos(a)), float(r * std::sin(a)),
                           float(-r * r / (2 * radius) + q.lift)});
  }
  const std::uint32_t n = std::uint32_t(ring.size());
  for (std::uint32_t i = 0; i < n; ++i) m.triangles.push_back({0, 1 + i, 1 + (i + 1) % n});
  return m;
}

TEST(SampledFits, DirectionsOnNearlyTwoLinesAreRefused) {
  // Four neighbours in two nearly opposite pairs (0 / 180.1 and 90 / 270.1 degrees), heights off
  // the sphere by +-0.01: the three unknowns hang on the 0.1 degree. Before: max |k| 11.7 for a
  // sphere of curvature 0.2, unflagged.
  const double R = 5;
  const Mesh m = sphere_fan({{0, 1, 0.01}, {90, 1, -0.01}, {180.1, 1, -0.01}, {270.1, 1, 0.01}}, R);
  const std::vector<Vec3f> up(m.vertex_count(), Vec3f{0, 0, 1});
  curvature::Options o;
  o.vertex_normals = &up;
  for (const auto& [name, fit] : sampled_fits()) {
    const CurvatureField f = fit(m, o);
    std::printf("  two lines, %-8s: unreliable %d, max |k| %.3g\n", name.c_str(),
                int(f.unreliable[0]), largest_curvature(f, 0));
    EXPECT_EQ(f.unreliable[0], 1) << name;
    EXPECT_EQ(f.H[0], 0.0f) << name << ": a flagged vertex holds zero curvature";
  }
  // The same ring spread evenly (0, 90, 180, 270 + 45 on the second pair): measured.
  const Mesh even = sphere_fan({{0, 1, 0}, {90, 1, 0}, {225, 1, 0}, {315, 1, 0}}, R);
  for (const auto& [name, fit] : sampled_fits()) {
    const CurvatureField f = fit(even, o);
    EXPECT_EQ(f.unreliable[0], 0) << name;
    EXPECT_NEAR(f.H[0], 1 / R, 0.01 / R) << name;
  }
}

TEST(SampledFits, ASampleFromATinyRaisedEdgeIsLeftOut) {
  // A regular hexagon on the sphere, and one more neighbour 0.01 away raised 0.008 (a sliver's
  // edge): its normal curvature 2 (P - q).n / |P - q|^2 is 98, past 2 / mean edge (2.2). Before:
  // sampling gave max |k| 32 for a sphere of curvature 0.2.
  const double R = 5;
  std::vector<FanNeighbour> hexagon;
  for (int i = 0; i < 6; ++i) hexagon.push_back({60.0 * i, 1, 0});
  std::vector<FanNeighbour> with_sliver = hexagon;
  with_sliver.insert(with_sliver.begin() + 1, FanNeighbour{30, 0.01, 0.008});
  const std::vector<Vec3f> up(with_sliver.size() + 1, Vec3f{0, 0, 1});
  curvature::Options o;
  o.vertex_normals = &up;
  for (const auto& [name, fit] : sampled_fits()) {
    const CurvatureField f = fit(sphere_fan(with_sliver, R), o);
    std::printf("  hexagon and a sliver, %-8s: unreliable %d, H %.4f (1/R %.4f)\n", name.c_str(),
                int(f.unreliable[0]), f.H[0], 1 / R);
    EXPECT_EQ(f.unreliable[0], 0) << name;
    EXPECT_NEAR(f.H[0], 1 / R, 0.02 / R) << name;
    EXPECT_NEAR(f.K[0], 1 / (R * R), 0.04 / (R * R)) << name;
  }
}

// The marching-cubes torus 64^3 with volume-gradient normals (EstimatorsMarchingCubes' mesh).
TEST(SampledFits, NoHugeValuesOnAMarchingCubesTorus) {
  openvdb::initialize();
  const auto field = datasets::make_field("torus");
  const volume::Volume vol = datasets::sample(*field, 64);
  const Mesh m = mc::extract(vol, float(field->isovalue()), Device::default_device());
  const std::vector<Vec3f> n = volume::gradient_normals(vol, m.positions);
  curvature::Options o;
  o.vertex_normals = &n;
  const double edge = mean_edge_length(m);
  for (const auto& [name, fit] : sampled_fits()) {
    const CurvatureField f = fit(m, o);
    std::size_t flagged = 0, over_2 = 0;
    double largest = 0;  // over the measured vertices, times the mean edge
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f.unreliable[i]) {
        ++flagged;
        continue;
      }
      const double k = largest_curvature(f, i) * edge;
      largest = std::max(largest, k);
      over_2 += k > 2;
    }
    std::printf("  torus 64^3 (%zu v) %-8s: %zu flagged, max |k| x mean edge %.3f, %zu over 2\n",
                m.vertex_count(), name.c_str(), flagged, largest, over_2);
    // 2 x the largest kept sample, each within 2 / mean edge (the one rule's bound)
    EXPECT_LE(largest, 4 * (1 + 1e-6)) << name;
    // the bulk stays measured (measured: quadric 272, sampling 406 of 8528)
    EXPECT_LT(double(flagged), 0.06 * double(m.vertex_count())) << name;
  }
}

}  // namespace
}  // namespace isocurv::test
