// The ambient-occlusion methods (ao/ao.h): the formulas' check values (SEEDS-SPEC.md A5, G-AO2,
// R-AO2, R-AO4), the ray cast against the closed forms inside a spherical cavity and on a plane,
// every method darker in concavities, determinism, compute()'s metadata and errors, and the
// curvature stage's own call running it (curvature::estimate_field's last step, apply_ao).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "ao/ao.h"
#include "ao/formulas.h"
#include "ao/griffin_exact.h"
#include "ao/raycast.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/estimator.h"
#include "curvature/reference.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract_reference.h"
#include "tests/curvature/test_meshes.h"
#include "volume/from_dense.h"
#include "volume/gradient_normals.h"

namespace isocurv {
namespace {

/// The definition by brute force: a periodic midpoint rule over n azimuths.
double griffin_trapezoid(double a1, double a2, bool cosine, int n) {
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const double phi = 2 * M_PI * (j + 0.5) / n, c = std::cos(phi), s = std::sin(phi);
    const double z = std::max(0.0, ao::horizon_height(-(a1 * c * c + a2 * s * s)));
    sum += cosine ? z * z : z;
  }
  return 1 - sum / n;
}

TEST(AoFormulas, GriffinExactMatchesTheQuadrature) {
  EXPECT_EQ(ao::griffin_exact(0, 0, 1), 1.0) << "a plane is fully open";
  EXPECT_EQ(ao::griffin_exact(3, 0.5, 2), 1.0) << "a convex point is fully open";
  // The concave umbilic diagonal: 1 - z(-rho k), and A5's figures for s = rho (k1 + k2).
  for (double k = -0.1; k > -20; k -= 0.37) {
    EXPECT_NEAR(ao::griffin_exact(k, k, 1), 1 - ao::horizon_height(-k), 1e-6);
    EXPECT_NEAR(ao::griffin_exact_integral(k, k, true), 1 - std::pow(ao::horizon_height(-k), 2),
                1e-6);
  }
  const double a5[][2] = {{-1, 0.7639}, {-2, 0.5858}, {-4, 0.3820}, {-8, 0.2192}, {-10, 0.1802}};
  for (const auto& [s, exact] : a5) EXPECT_NEAR(ao::griffin_exact(s / 2, s / 2, 1), exact, 1e-4);
  // Against a 4096-azimuth quadrature everywhere: saddles, cylinders, both signs, large |rho k|.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-12, 12);
  double worst = 0;
  for (int t = 0; t < 4000; ++t) {
    double a1 = u(rng), a2 = u(rng);
    if (t % 4 == 1) a2 = 0;  // cylinders: the kink on an axis
    if (t % 4 == 2) a1 *= 1e-3;
    for (bool cosine : {false, true})
      worst = std::max(worst, std::abs(ao::griffin_exact_integral(a1, a2, cosine) -
                                       griffin_trapezoid(a1, a2, cosine, 4096)));
  }
  std::printf("griffin-exact vs 4096-azimuth quadrature: max |diff| %.2e\n", worst);
  EXPECT_LT(worst, 1e-5);
  // The existing polynomial against the exact diagonal, s = rho (k1 + k2): SEEDS-SPEC asks for
  // 0.01 over [-10, -2], but its own table A5 has them 0.038 apart at s = -8: they agree at the
  // ends; in between the gap is printed.
  double gap = 0;
  for (double s = -10; s <= -2; s += 0.25)
    gap = std::max(gap, std::abs(curvature::ambient_occlusion(s / 2, s / 2, 1.0) -
                                 ao::griffin_exact(s / 2, s / 2, 1)));
  std::printf("griffin polynomial vs exact on the diagonal, s in [-10, -2]: max gap %.4f\n", gap);
  EXPECT_NEAR(curvature::ambient_occlusion(-1.0, -1.0, 1.0), ao::griffin_exact(-1, -1, 1), 0.01);
  EXPECT_NEAR(curvature::ambient_occlusion(-5.0, -5.0, 1.0), ao::griffin_exact(-5, -5, 1), 0.01);
  EXPECT_LT(gap, 0.09);
}

TEST(AoFormulas, HattoriAndPrantlCheckValues) {
  EXPECT_EQ(ao::hattori(0, 0, 1), 1.0);
  EXPECT_EQ(ao::hattori(1, 0.5, 1), 1.0);
  EXPECT_NEAR(ao::hattori(-1, -1, 1, /*half=*/true), 0.7281, 1e-4);  // A5 at s = -2
  EXPECT_NEAR(ao::hattori(-1, -1, 1), 0.5759, 1e-4);  // the printed form: A5's s = -4 entry
  EXPECT_NEAR(ao::prantl(0, 1), 0.9, 1e-12);
  EXPECT_NEAR(ao::prantl(-1e-12, 1), 0.9, 1e-9) << "continuous at 0 from the concave side";
  EXPECT_NEAR(ao::prantl(-1, 1), 0.9 * std::exp(-2.5), 1e-12);
  EXPECT_NEAR(ao::prantl(-1, 1), 0.0739, 1e-4);
  EXPECT_NEAR(ao::prantl(1, 1), 1.0, 1e-12);
  EXPECT_NEAR(ao::prantl(-5, 1), ao::prantl(-1, 1), 1e-12) << "clamped beyond H_ref";
}

// Every formula falls as the surface closes in: along the concave umbilic diagonal and along
// saddles with k1 > 0 fixed and k2 more and more negative.
TEST(AoFormulas, EveryFormulaDecreasesIntoConcavities) {
  const double rho = 1, href = 5;
  double prev[5] = {2, 2, 2, 2, 2};
  for (double k = 0; k >= -4.0; k -= 0.25) {
    const double v[5] = {curvature::ambient_occlusion(k, k, rho), ao::griffin_exact(k, k, rho),
                         ao::hattori(k, k, rho), ao::hattori(k, k, rho, true), ao::prantl(k, href)};
    for (int m = 0; m < 5; ++m) {
      EXPECT_LT(v[m], prev[m]) << "method " << m << " at k " << k;
      prev[m] = v[m];
    }
  }
  double p_exact = 2;
  for (double k2 = -0.5; k2 >= -8; k2 -= 0.5) {
    const double v = ao::griffin_exact(0.3, k2, rho);
    EXPECT_LT(v, p_exact) << "saddle k2 " << k2;
    p_exact = v;
  }
}

/// The sphere field |p| - 0.8 sampled at n^3 ([-1, 1]^3), as a ball (Inside::Below, its own)
/// or a spherical cavity in a solid (Inside::Above), with its isosurface and gradient normals.
struct SphereCase {
  volume::Volume volume;
  Mesh mesh;
  curvature::CurvatureField field;
};
SphereCase sphere_case(int n, bool cavity) {
  const auto f = datasets::make_field("sphere");
  SphereCase s{datasets::sample(*f, n), {}, {}};
  if (cavity) s.volume.inside = volume::Inside::Above;
  s.mesh = mc::extract_reference(s.volume, 0.0f);
  const volume::MeshNormals normals = volume::gradient_normals_for_mesh(s.volume, s.mesh);
  curvature::Options o;
  o.vertex_normals = &normals.normals;
  o.ao_scale = 0.2f;
  s.field = curvature::estimate_reference(s.mesh, o);
  return s;
}

TEST(AoRaycast, SphericalCavityMatchesTheClosedForms) {
  const double R = 0.8;
  const SphereCase s = sphere_case(96, true);  // R = 38 voxels
  // Every 16th vertex (the closed form holds at every point of the cavity's wall).
  Positions p;
  std::vector<Vec3f> n;
  for (std::size_t v = 0; v < s.mesh.vertex_count(); v += 16) {
    p.push_back(s.mesh.positions[v]);
    n.push_back(s.field.normals[v]);
    // the normal points into the cavity (out of the solid around it)
    ASSERT_LT(p.back()[0] * n.back()[0] + p.back()[1] * n.back()[1] + p.back()[2] * n.back()[2], 0);
  }
  for (double f : {0.2, 0.5}) {
    for (bool cosine : {false, true}) {
      ao::RaycastOptions o;
      o.radius = f * R;
      o.cosine = cosine;
      const std::vector<float> ao = ao::raycast(s.volume, 0.0f, p, n, o);
      double mean = 0, worst = 0;
      const double c = f / 2, exact = cosine ? 1 - c * c : 1 - c;
      for (float a : ao) mean += a, worst = std::max(worst, std::abs(a - exact));
      mean /= double(ao.size());
      std::printf(
          "cavity R=38 voxels, rho=%.1fR, %s: mean AO %.5f, exact %.5f (rel %.2e), worst "
          "vertex %.4f, %zu vertices\n",
          f, cosine ? "cosine" : "uniform", mean, exact, std::abs(mean / exact - 1), worst,
          ao.size());
      EXPECT_NEAR(mean / exact, 1, 0.01);
      EXPECT_LT(worst, 0.05) << "every vertex, 256 stratified rays";
    }
  }
}

TEST(AoRaycast, PlaneIsFullyOpenAndRunsAreDeterministic) {
  // value = z - 10.3 voxels, the object below (Inside::Below): a plane facing +z.
  const int n = 24;
  std::vector<float> data(std::size_t(n) * n * n);
  for (int z = 0, i = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) data[std::size_t(i++)] = float(z - 10.3);
  const volume::Volume v = volume::from_dense(
      data.data(), {n, n, n}, openvdb::math::Transform::createLinearTransform(0.5),
      {"generated:plane", "generated", "float", "plane", volume::Inside::Below});
  const Mesh mesh = mc::extract_reference(v, 0.0f);
  const volume::MeshNormals normals = volume::gradient_normals_for_mesh(v, mesh);
  ASSERT_GT(mesh.vertex_count(), 100u);
  ao::RaycastOptions o;
  o.radius = 1.5;  // 3 voxels
  for (bool cosine : {false, true}) {
    o.cosine = cosine;
    const std::vector<float> a = ao::raycast(v, 0.0f, mesh.positions, normals.normals, o);
    for (float x : a) ASSERT_EQ(x, 1.0f);
  }
  // Determinism, where rays do hit: the cavity, twice, bit for bit.
  const SphereCase s = sphere_case(40, true);
  o.radius = 0.3;
  o.cosine = false;
  const std::vector<float> a = ao::raycast(s.volume, 0.0f, s.mesh.positions, s.field.normals, o);
  const std::vector<float> b = ao::raycast(s.volume, 0.0f, s.mesh.positions, s.field.normals, o);
  EXPECT_EQ(a, b);
  double mean = 0;
  for (float x : a) mean += x;
  std::printf("cavity 40^3 rho 0.3: mean %.4f (closed form %.4f)\n", mean / double(a.size()),
              1 - 0.3 / 1.6);
  EXPECT_LT(mean / double(a.size()), 0.9) << "the rays reach the cavity's wall";
}

TEST(AoCompute, PlaneGivesEachMethodsFlatValue) {
  const Mesh plane = test::quadric_patch(21, 1.0f, 0, 0);
  curvature::CurvatureField field = curvature::estimate_reference(plane);
  for (auto* a : {&field.k1, &field.k2, &field.H}) std::fill(a->begin(), a->end(), 0.0f);
  const struct {
    ao::Method m;
    float flat;
  } cases[] = {{ao::Method::griffin, float(curvature::kAoC0)},
               {ao::Method::griffin_exact, 1.0f},
               {ao::Method::hattori, 1.0f},
               {ao::Method::prantl, 0.9f}};
  for (const auto& c : cases) {
    ao::Options o;
    o.method = c.m;
    o.radius = 0.2;
    ao::compute(plane, field, {}, o);
    for (float x : field.ao) ASSERT_FLOAT_EQ(x, c.flat) << ao::method_name(c.m);
  }
}

// On marching-cubes spheres of radius 0.8: every method gives the cavity less AO than the ball,
// and the ray cast (the reference) agrees with the closed form; metadata names the method.
TEST(AoCompute, EveryMethodIsDarkerInTheCavityAndNamesItself) {
  const SphereCase ball = sphere_case(48, false), cavity = sphere_case(48, true);
  for (ao::Method m : {ao::Method::griffin, ao::Method::griffin_exact, ao::Method::hattori,
                       ao::Method::prantl, ao::Method::raycast, ao::Method::raycast_cos}) {
    double mean[2];
    for (int c = 0; c < 2; ++c) {
      SphereCase s = c ? cavity : ball;  // a copy: compute() replaces the AO
      ao::Options o;
      o.method = m;
      o.radius = 0.2;
      ao::compute(s.mesh, s.field, {&s.volume, 0.0f}, o);
      ASSERT_EQ(s.field.ao.size(), s.mesh.vertex_count());
      mean[c] = 0;
      for (float x : s.field.ao) mean[c] += x;
      mean[c] /= double(s.field.ao.size());
      std::size_t named = 0;
      for (const auto& [k, v] : s.field.metadata) named += k == "ao" && v == ao::method_name(m);
      EXPECT_EQ(named, 1u) << ao::method_name(m);
    }
    std::printf("%-14s ball %.4f  cavity %.4f\n", ao::method_name(m), mean[0], mean[1]);
    EXPECT_LT(mean[1], mean[0]) << ao::method_name(m);
    if (m == ao::Method::raycast) {
      EXPECT_NEAR(mean[0], 1.0, 1e-3);
      EXPECT_NEAR(mean[1], 1 - 0.2 / 1.6, 0.01);
    }
  }
  // griffin through compute() is the estimators' own AO
  SphereCase s = cavity;
  const std::vector<float> own = s.field.ao;
  ao::Options o;
  o.radius = 0.2;
  ao::compute(s.mesh, s.field, {}, o);
  ASSERT_EQ(s.field.ao.size(), own.size());
  for (std::size_t i = 0; i < own.size(); ++i) ASSERT_NEAR(s.field.ao[i], own[i], 1e-6);
}

// The curvature stage's call: estimate_field with Options::ao_method gives what ao::compute gives
// on its griffin field, bit for bit (array and metadata); griffin is the estimators' own AO.
TEST(AoCompute, TheCurvatureStageRunsIt) {
  const SphereCase s = sphere_case(32, true);
  const curvature::VolumeSource source{&s.volume, 0.0f};
  curvature::Options co;
  co.ao_scale = 0.2f;
  curvature::EstimatorReport griffin_report;
  const curvature::CurvatureField griffin =
      curvature::estimate_field(s.mesh, source, nullptr, co, &griffin_report);
  EXPECT_FALSE(griffin_report.ao_ms) << "griffin: no AO step";
  for (ao::Method m : {ao::Method::griffin_exact, ao::Method::hattori, ao::Method::prantl,
                       ao::Method::raycast}) {
    for (bool half : {false, true}) {
      if (half && m != ao::Method::hattori) continue;
      co.ao_method = m;
      co.hattori_half = half;
      curvature::EstimatorReport r;
      const curvature::CurvatureField staged =
          curvature::estimate_field(s.mesh, source, nullptr, co, &r);
      curvature::CurvatureField expected = griffin;
      ao::Options o;
      o.method = m;
      o.radius = 0.2f;
      o.hattori_half = half;
      ao::compute(s.mesh, expected, source, o);
      EXPECT_EQ(staged.ao, expected.ao) << ao::method_name(m);
      EXPECT_EQ(staged.metadata, expected.metadata) << ao::method_name(m);
      EXPECT_NE(staged.ao, griffin.ao) << ao::method_name(m);
      EXPECT_TRUE(r.ao_ms) << ao::method_name(m);
      // the same step on a field estimated before (a file's own curvature)
      curvature::CurvatureField later = griffin;
      EXPECT_TRUE(curvature::apply_ao(s.mesh, later, source, co));
      EXPECT_EQ(later.ao, expected.ao) << ao::method_name(m);
    }
  }
  co.ao_method = ao::Method::griffin;
  co.hattori_half = false;
  curvature::CurvatureField unchanged = griffin;
  EXPECT_FALSE(curvature::apply_ao(s.mesh, unchanged, source, co));
  EXPECT_EQ(unchanged.ao, griffin.ao);
  co.ao_method = ao::Method::raycast;
  EXPECT_THROW(curvature::estimate_field(s.mesh, {}, nullptr, co), Error)
      << "a ray cast without the volume (resolve refuses it first)";
}

TEST(AoCompute, BadRequestsAreErrors) {
  const Mesh sphere = test::icosphere(2, 1);
  curvature::CurvatureField field = curvature::estimate_reference(sphere);
  ao::Options o;
  o.method = ao::Method::raycast;
  EXPECT_THROW(ao::compute(sphere, field, {}, o), Error) << "a ray cast needs the volume";
  o.method = ao::Method::hattori;
  o.radius = 0;
  EXPECT_THROW(ao::compute(sphere, field, {}, o), Error);
  o.radius = NAN;
  EXPECT_THROW(ao::compute(sphere, field, {}, o), Error);
  o.radius = 1;
  field.k1.pop_back();
  EXPECT_THROW(ao::compute(sphere, field, {}, o), Error);
  EXPECT_EQ(ao::method_from_name("raycast-cos"), ao::Method::raycast_cos);
  EXPECT_FALSE(ao::method_from_name("guess"));
}

}  // namespace
}  // namespace isocurv
