// Neighbourhood features (features/features.h) against closed forms: spheres, a
// plane, a torus, and a CT-like ball (blurred edge, uint8, noise), on analytic
// meshes and marching-cubes meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "core/error.h"
#include "curvature/reference.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "features/features.h"
#include "mc/extract_reference.h"
#include "tests/curvature/test_meshes.h"
#include "tests/features/feature_helpers.h"
#include "volume/from_dense.h"
#include "volume/gradient_normals.h"

namespace isocurv {
namespace {

using test::array;
using test::compare;
using test::ct_ball;
using test::Error2;
using test::surface_of;
using test::VolumeSurface;

constexpr double kPi = 3.14159265358979323846;

/// An icosphere of radius R with exact normals and the reference's Voronoi
/// areas.
struct SphereMesh {
  Mesh mesh;
  curvature::CurvatureField field;
};
SphereMesh sphere_mesh(int level, float R) {
  SphereMesh s{test::icosphere(level, R), {}};
  std::vector<Vec3f> normals;
  for (const Vec3f &p : s.mesh.positions)
    normals.push_back({p[0] / R, p[1] / R, p[2] / R});
  curvature::Options o;
  o.vertex_normals = &normals;
  s.field = curvature::estimate_reference(s.mesh, o);
  return s;
}

TEST(Features, SphereMeshLbeIsExactAndTheHorizonFormHasThePapersBias) {
  const float R = 2;
  const SphereMesh s = sphere_mesh(6, R); // 40962 vertices, edge ~0.017 R
  for (double f : {0.25, 0.5}) {
    features::Options o;
    o.radii = {f * R};
    o.features = {features::Feature::LBE, features::Feature::NSV,
                  features::Feature::H_ii};
    const features::FeatureField out =
        features::compute(s.mesh, s.field, nullptr, o);
    const std::vector<double> inv_r2(s.mesh.vertex_count(), 1 / (R * R)),
        inv_r(s.mesh.vertex_count(), 1 / R);
    const Error2 lbe = compare(array(out, "LBE"), inv_r2, out.boundary);
    const Error2 hmesh = compare(array(out, "H_ii"), inv_r, out.boundary);
    // H implied by the horizon NSV: Vr = (4 pi r^3 / 3)(1 - NSV), H = 8/(3r) -
    // 4 Vr / (pi r^4).
    const double r = f * R;
    double nsv = 0;
    for (float v : array(out, "NSV"))
      nsv += v;
    nsv /= double(s.mesh.vertex_count());
    const double vr = 4 * kPi * r * r * r / 3 * (1 - nsv);
    const double h_horizon = 8 / (3 * r) - 4 * vr / (kPi * r * r * r * r);
    std::printf("sphere mesh r=%.2fR: LBE rel.rms %.2e, H_ii(surface) rel.rms "
                "%.4f, H(horizon NSV)*R %.4f\n",
                f, lbe.rel_rms, hmesh.rel_rms, h_horizon * R);
    EXPECT_EQ(lbe.count, s.mesh.vertex_count())
        << "a closed sphere has no boundary";
    EXPECT_LT(lbe.rel_rms, 1e-4);
    EXPECT_LT(hmesh.rel_rms, 0.02);
    EXPECT_NEAR(h_horizon * R, 8.0 / 9.0, 0.005)
        << "the paper's known 8/9 bias";
  }
}

TEST(Features, PlaneGivesZeroBendingHalfVolumeAndZeroCurvature) {
  const Mesh plane = test::quadric_patch(41, 1.0f, 0, 0);
  curvature::CurvatureField field = curvature::estimate_reference(plane);
  features::Options o;
  o.radii = {0.3};
  const features::FeatureField out =
      features::compute(plane, field, nullptr, o);
  const auto &lbe = array(out, "LBE");
  const auto &nsv = array(out, "NSV");
  const auto &h = array(out, "H_ii");
  const auto &k = array(out, "K_ii");
  std::size_t inner = 0;
  for (std::size_t v = 0; v < plane.vertex_count(); ++v) {
    if (out.boundary[v])
      continue;
    ++inner;
    EXPECT_NEAR(lbe[v], 0, 1e-6);
    EXPECT_NEAR(nsv[v], 0.5, 1e-6);
    EXPECT_NEAR(h[v], 0, 1e-5);
    EXPECT_NEAR(k[v], 0, 0.02 / (0.3 * 0.3))
        << "flat: the geodesic disc is the plane disc";
  }
  EXPECT_GT(inner, plane.vertex_count() / 4)
      << "vertices farther than r from the border";
  EXPECT_LT(inner, plane.vertex_count())
      << "vertices near the open border are flagged";
}

TEST(Features, GeodesicDiscGivesGaussianCurvatureOnASphere) {
  const float R = 1;
  const SphereMesh s = sphere_mesh(5, R);
  features::Options o;
  o.radii = {0.5 * R};
  o.features = {features::Feature::K_ii, features::Feature::SI_ii};
  const features::FeatureField out =
      features::compute(s.mesh, s.field, nullptr, o);
  // On the sphere GA = 2 pi R^2 (1 - cos(r/R)): the series 12 (pi r^2 - GA) /
  // (pi r^4) would give 1/R^2 - r^2/(30 R^4) (0.992 here); solving the disc
  // formula gives 1/R^2.
  const double r = 0.5 * R, ga = 2 * kPi * R * R * (1 - std::cos(r / R));
  const double k_series = 12 * (kPi * r * r - ga) / (kPi * r * r * r * r);
  const Error2 k = compare(
      array(out, "K_ii"),
      std::vector<double>(s.mesh.vertex_count(), 1 / (R * R)), out.boundary);
  const Error2 si =
      compare(array(out, "SI_ii"),
              std::vector<double>(s.mesh.vertex_count(), 1.0), out.boundary);
  std::printf("sphere mesh r=0.5R: K_ii mean %.4f (series %.4f, 1/R^2 = 1), "
              "rel.rms %.3f; SI_ii mean %.4f\n",
              k.mean, k_series, k.rel_rms, si.mean);
  EXPECT_LT(k.rel_rms, 0.03);
  EXPECT_LT(std::abs(k.mean - 1), std::abs(1 - k_series) + 0.02);
  // The shape index of an umbilic point is as sensitive as it gets: K a
  // fraction e below H^2 gives SI = 1 - (2/pi) sqrt(e), so K's 2% costs about
  // 0.09 here.
  EXPECT_GT(si.mean, 0.85);
}

TEST(Features, VolumeIntegralInvariantGivesMeanCurvatureOnTheSphereField) {
  const auto field = datasets::make_field("sphere"); // |p| - 0.8, a level set
  VolumeSurface s = surface_of(datasets::sample(*field, 64), field->isovalue());
  const double R = 0.8; // 25 voxels
  for (double f : {0.1, 0.25, 0.5}) {
    features::Options o;
    o.radii = {f * R};
    o.features = {features::Feature::Vr, features::Feature::H_ii};
    o.isovalue = s.iso;
    const features::FeatureField out =
        features::compute(s.mesh, s.field, &s.volume, o);
    const Error2 h = compare(array(out, "H_ii"),
                             std::vector<double>(s.mesh.vertex_count(), 1 / R),
                             out.boundary);
    std::printf("sphere field 64^3 r=%.2fR: H_ii*R %.5f, rel.rms %.4f\n", f,
                h.mean * R, h.rel_rms);
    EXPECT_NEAR(h.mean * R, 1, 0.01);
    EXPECT_LT(h.rel_rms, 0.02);
    // Vr itself: the lens volume 2 pi r^3 / 3 - pi r^4 / (4R), within the
    // trilinear surface's error.
    const double r = f * R,
                 lens = 2 * kPi * r * r * r / 3 - kPi * r * r * r * r / (4 * R);
    const Error2 vr =
        compare(array(out, "Vr"),
                std::vector<double>(s.mesh.vertex_count(), lens), out.boundary);
    EXPECT_LT(vr.rel_rms, 0.01);
  }
}

TEST(Features, TorusFieldMeanCurvatureAtSmallRadius) {
  const auto field =
      datasets::make_field("torus"); // tube 0.25 about a circle of radius 0.6
  VolumeSurface s = surface_of(datasets::sample(*field, 96), field->isovalue());
  std::vector<double> exact(s.mesh.vertex_count()), c2(s.mesh.vertex_count());
  for (std::size_t v = 0; v < exact.size(); ++v) {
    const Vec3f &p = s.mesh.positions[v];
    const datasets::SurfaceCurvature c = datasets::exact_curvature(
        *field, datasets::project_to_surface(*field, {p[0], p[1], p[2]}));
    exact[v] = c.H;
    c2[v] = 0.5 * (c.k1 * c.k1 + c.k2 * c.k2);
  }
  for (double r : {0.05, 0.1}) {
    features::Options o;
    o.radii = {r};
    o.features = {features::Feature::H_ii, features::Feature::LBE};
    o.isovalue = s.iso;
    const features::FeatureField out =
        features::compute(s.mesh, s.field, &s.volume, o);
    const Error2 h = compare(array(out, "H_ii"), exact, out.boundary);
    const Error2 lbe = compare(array(out, "LBE"), c2, out.boundary);
    std::printf("torus field 96^3 r=%.2f: H_ii rel.rms %.4f (bias grows with r), "
                "LBE vs Curvedness^2 rel.rms %.4f\n",
                r, h.rel_rms, lbe.rel_rms);
    EXPECT_LT(h.rel_rms, 0.05);
    // LBE on the marching-cubes torus (volume normals): measured 0.044 at r = 0.05 (about 2.5
    // voxels: few neighbours) and 0.0116 at r = 0.1, asserted with a 1.5x margin.
    EXPECT_LT(lbe.rel_rms, r < 0.075 ? 0.066 : 0.018);
  }
}

TEST(Features, TorusLbeTendsToCurvednessSquared) {
  // A-LBE: as r -> 0, LBE -> Curvedness^2 = (k1^2 + k2^2) / 2. Torus(1, 0.4) with exact
  // normals and the reference's Voronoi areas, r = 0.1, every vertex.
  std::vector<double> errors;
  for (int n : {120, 240, 480}) {
    const test::Torus t = test::torus(1.0, 0.4, n, 2 * n / 5);
    std::vector<Vec3f> normals;
    std::vector<double> c2;
    for (std::size_t v = 0; v < t.mesh.vertex_count(); ++v) {
      const Eigen::Vector3d nv = t.normal(v);
      normals.push_back({float(nv.x()), float(nv.y()), float(nv.z())});
      c2.push_back(0.5 * (t.k1(v) * t.k1(v) + t.k2(v) * t.k2(v)));
    }
    curvature::Options co;
    co.vertex_normals = &normals;
    const curvature::CurvatureField field = curvature::estimate_reference(t.mesh, co);
    features::Options o;
    o.radii = {0.1};
    o.features = {features::Feature::LBE};
    const features::FeatureField out = features::compute(t.mesh, field, nullptr, o);
    const Error2 e = compare(array(out, "LBE"), c2, out.boundary);
    std::printf("torus(1, 0.4) %dx%d, r = 0.1: LBE vs Curvedness^2 rel.rms %.4f\n", t.nu, t.nv,
                e.rel_rms);
    EXPECT_EQ(e.count, t.mesh.vertex_count()) << "a closed torus has no boundary";
    errors.push_back(e.rel_rms);
  }
  // At a fixed r the error is the discrete sum's (it falls as the mesh refines; measured 0.107,
  // 0.0267, 0.0074: second order, 4.0x and 3.6x per doubling) plus the continuum's O(r^2) bias,
  // which the 0.0074 bounds. Asserted: at least first order (each doubling at least halves the
  // error), and at 480x192 the spec's reference computation (Appendix A6: 0.0074) within a
  // 1.5x margin (the spec's acceptance line allows 0.02).
  EXPECT_LT(errors[1], 0.5 * errors[0]);
  EXPECT_LT(errors[2], 0.5 * errors[1]);
  EXPECT_LT(errors[2], 1.5 * 0.0074);
}

TEST(Features, CtLikeBallMeanCurvatureBeatsPerVertexCurvature) {
  const double R = 20;
  VolumeSurface s = surface_of(ct_ball(56, R), 120);
  std::vector<double> exact(s.mesh.vertex_count(), 1 / R);
  std::vector<float> per_vertex(s.field.H.begin(), s.field.H.end());
  const Error2 pv =
      compare(per_vertex, exact, std::vector<std::uint8_t>(exact.size(), 0));
  for (double r : {4.0, 6.0}) {
    features::Options o;
    o.radii = {r};
    o.features = {features::Feature::H_ii};
    o.isovalue = s.iso;
    const features::FeatureField out =
        features::compute(s.mesh, s.field, &s.volume, o);
    const Error2 h = compare(array(out, "H_ii"), exact, out.boundary);
    std::printf("CT-like ball R=20 voxels, uint8, noise +-4: H_ii (r = %g "
                "voxels) rel.rms %.4f, per-vertex H "
                "(volume normals) rel.rms %.4f\n",
                r, h.rel_rms, pv.rel_rms);
    EXPECT_LT(h.rel_rms, 0.05);
    EXPECT_LT(h.rel_rms, 0.25 * pv.rel_rms);
  }
}

TEST(Features, SeveralRadiiGetSuffixesAndRunsAreDeterministic) {
  const SphereMesh s = sphere_mesh(3, 1);
  features::Options o;
  o.radii = {0.2, 0.4};
  o.radius_names = {"0.2", "0.4"};
  o.features = {features::Feature::LBE, features::Feature::SI_ii};
  const features::FeatureField a =
      features::compute(s.mesh, s.field, nullptr, o);
  const features::FeatureField b =
      features::compute(s.mesh, s.field, nullptr, o);
  ASSERT_EQ(a.arrays.size(), 4u);
  EXPECT_EQ(a.arrays[0].name, "LBE_r0.2");
  EXPECT_EQ(a.arrays[1].name, "SI_ii_r0.2");
  EXPECT_EQ(a.arrays[3].name, "SI_ii_r0.4");
  for (std::size_t i = 0; i < a.arrays.size(); ++i)
    EXPECT_EQ(a.arrays[i].values, b.arrays[i].values);
}

TEST(Features, BadRequestsAreErrors) {
  const SphereMesh s = sphere_mesh(2, 1);
  features::Options o;
  o.radii = {0};
  EXPECT_THROW(features::compute(s.mesh, s.field, nullptr, o), Error);
  o.radii = {10}; // larger than the sphere's bounding box diagonal (2 sqrt 3)
  EXPECT_THROW(features::compute(s.mesh, s.field, nullptr, o), Error);
  o.radii = {0.3};
  o.features = {features::Feature::Vr};
  EXPECT_THROW(features::compute(s.mesh, s.field, nullptr, o), Error)
      << "Vr needs a volume";
  EXPECT_THROW(features::parse_features("LBE,curvature"), Error);
  EXPECT_EQ(features::parse_features("all").size(), 6u);
  curvature::CurvatureField empty;
  o.features = {features::Feature::LBE};
  EXPECT_THROW(features::compute(s.mesh, empty, nullptr, o), Error);
}

TEST(Features, DegenerateInputStaysFinite) {
  Mesh m;
  m.positions = {{0, 0, 0},
                 {1, 0, 0},
                 {0, 1, 0},
                 {0.5f, 0.5f, 0},
                 {5, 5, 5}}; // a triangle, a
  m.triangles = {{0, 1, 2},
                 {1, 3, 3}}; // degenerate one, and an isolated vertex
  const curvature::CurvatureField f = curvature::estimate_reference(m);
  features::Options o;
  o.radii = {0.5};
  const features::FeatureField out = features::compute(m, f, nullptr, o);
  for (const auto &a : out.arrays)
    for (float v : a.values)
      EXPECT_TRUE(std::isfinite(v)) << a.name;
  EXPECT_EQ(out.boundary[4], 1) << "the isolated vertex is flagged";
  EXPECT_EQ(out.boundary[0], 1) << "an open triangle's corners are flagged";
}

} // namespace
} // namespace isocurv
