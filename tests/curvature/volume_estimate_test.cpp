// The volume estimator (curvature/volume_estimate.h): the OpenCL kernel against its double
// reference, accuracy against the exact curvature of analytic fields (second-order convergence,
// signs, density versus level set, anisotropic and rotated grids), CT-like volumes (blurred,
// quantised, noisy) at the automatic scale, the finer-scale fallback on thin structures, and bad
// input.
#include "curvature/volume_estimate.h"

#include <gtest/gtest.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include "compare.h"
#include "core/cl_device.h"
#include "curvature/auto_scale.h"
#include "curvature/estimator.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "volume/from_dense.h"

namespace isocurv::test {
namespace {

// Options at a fixed scale, the level set through the vertex unless told otherwise.
curvature::VolumeOptions volume_options_at(
    double sigma, float ao_scale, curvature::VolumePoint point = curvature::VolumePoint::vertex) {
  curvature::VolumeOptions o = curvature::fixed_scale(sigma, ao_scale);
  o.point = point;
  return o;
}

// f(world) sampled on dims voxels at world = origin + R diag(spacing) index.
volume::Volume sample_affine(const std::function<double(const Eigen::Vector3d&)>& f,
                             std::array<int, 3> dims, const Eigen::Vector3d& spacing,
                             const Eigen::Vector3d& origin, const Eigen::Matrix3d& R,
                             volume::Inside inside, const std::string& voxel_type = "float") {
  const Eigen::Matrix3d A = R * spacing.asDiagonal();
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::size_t i = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) data[i++] = float(f(origin + A * Eigen::Vector3d(x, y, z)));
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();  // row-vector convention: p' = p m
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(c, r) = A(r, c);
  for (int r = 0; r < 3; ++r) m(3, r) = origin[r];
  volume::DenseSource src;
  src.path = "test";
  src.format = "generated";
  src.voxel_type = voxel_type;
  src.inside = inside;
  return volume::from_dense(data.data(), dims, openvdb::math::Transform::createLinearTransform(m),
                            src);
}

// RMS relative errors of H and K over vertices, against exact values given per vertex.
struct Errors {
  double H = 0, K = 0;
};

Errors errors(const curvature::CurvatureField& f, const std::vector<double>& H,
              const std::vector<double>& K) {
  double eh = 0, ek = 0, nh = 0, nk = 0;
  for (std::size_t i = 0; i < H.size(); ++i) {
    eh += (f.H[i] - H[i]) * (f.H[i] - H[i]), nh += H[i] * H[i];
    ek += (f.K[i] - K[i]) * (f.K[i] - K[i]), nk += K[i] * K[i];
  }
  return {std::sqrt(eh / nh), std::sqrt(ek / nk)};
}

// Exact H, K of an analytic field at the projections of the mesh's vertices.
void exact(const datasets::Field& field, const Mesh& m, std::vector<double>& H,
           std::vector<double>& K) {
  H.clear(), K.clear();
  for (const Vec3f& p : m.positions) {
    const Eigen::Vector3d q =
        datasets::project_to_surface(field, Eigen::Vector3d(p[0], p[1], p[2]));
    const datasets::SurfaceCurvature c = datasets::exact_curvature(field, q);
    H.push_back(c.H), K.push_back(c.K);
  }
}

struct Case {
  volume::Volume volume;
  float iso = 0;
  Mesh mesh;
};

Case catalogue(const std::string& name, int resolution) {
  openvdb::initialize();
  const auto field = datasets::make_field(name);
  Case c{datasets::sample(*field, resolution), float(field->isovalue()), {}};
  c.mesh = mc::extract(c.volume, c.iso, Device::default_device());
  return c;
}

double voxel_of(const volume::Volume& v) {
  const openvdb::Vec3d s = v.spacing();
  return std::max({s[0], s[1], s[2]});
}

// A sparse OpenVDB level set (narrow band of 3 voxels, tiles inside and out): no domain to clamp
// to, background outside the band, leaves missing where the prefilter reaches past the band.
Case level_set_sphere() {
  openvdb::initialize();
  Case c;
  c.volume.grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      9.0f, openvdb::Vec3f(0.3f, -0.2f, 0.1f), 0.5f, 3.0f);
  c.volume.dense = false;
  c.volume.inside = volume::Inside::Below;
  c.volume.domain = c.volume.grid->evalActiveVoxelBoundingBox();
  c.iso = 0;
  c.mesh = mc::extract(c.volume, c.iso, Device::default_device());
  return c;
}

TEST(VolumeEstimator, KernelMatchesReference) {
  using curvature::VolumePoint;
  for (const Case& c : {catalogue("torus", 40), level_set_sphere()}) {
    // 4.5 and 9 voxels read the pyramid's levels 1 and 2 (volume/pyramid.h), and their finer
    // scales the levels under them.
    for (const auto& [voxels, point] : {std::pair{1.0, VolumePoint::vertex},
                                        std::pair{2.3, VolumePoint::vertex},
                                        std::pair{1.7, VolumePoint::surface},
                                        std::pair{4.5, VolumePoint::vertex},
                                        std::pair{9.0, VolumePoint::surface}}) {
      const double sigma = voxels * voxel_of(c.volume);
      const curvature::CurvatureField ref = curvature::volume_estimate_reference(
          c.mesh, c.volume, c.iso, volume_options_at(sigma, 0.1f, point));
      curvature::VolumeEstimateStats st;
      const curvature::CurvatureField dev =
          curvature::volume_estimate(c.mesh, c.volume, c.iso, volume_options_at(sigma, 0.1f, point),
                                     Device::default_device(), &st);
      EXPECT_GT(st.bricks, 0u);
      const FieldDifference d = compare(dev, ref, 0.5);
      // Float against double: prefilter sums of up to 37 taps, then 125 weighted samples.
      EXPECT_LT(d.H, 1e-4) << d.str();
      EXPECT_LT(d.K, 1e-4) << d.str();
      EXPECT_LT(d.k1, 1e-4) << d.str();
      EXPECT_LT(d.k2, 1e-4) << d.str();
      EXPECT_LT(d.normal_angle, 2e-3) << d.str();
      EXPECT_LT(d.dir_angle, 1e-2) << d.str();
      EXPECT_LT(d.dcurv, 1e-2) << d.str();
      EXPECT_TRUE(d.same_boundary);
      EXPECT_EQ(dev.unreliable, ref.unreliable);
      // The surface points (measure::object_measures integrates over them): Newton steps and the
      // shrinkage in float against double (surface), the edge correction from the curvature
      // (vertex); both well under a thousandth of a voxel.
      ASSERT_EQ(dev.surface_points.size(), c.mesh.positions.size());
      ASSERT_EQ(ref.surface_points.size(), c.mesh.positions.size());
      double worst = 0, moved = 0;
      for (std::size_t i = 0; i < c.mesh.positions.size(); ++i) {
        double d2 = 0, m2 = 0;
        for (int a = 0; a < 3; ++a) {
          d2 += std::pow(double(dev.surface_points[i][a]) - ref.surface_points[i][a], 2);
          m2 += std::pow(double(ref.surface_points[i][a]) - c.mesh.positions[i][a], 2);
        }
        worst = std::max(worst, std::sqrt(d2));
        moved = std::max(moved, std::sqrt(m2));
      }
      EXPECT_LT(worst, 1e-3 * voxel_of(c.volume));
      EXPECT_GT(moved, 1e-3 * voxel_of(c.volume)) << "the points are not the vertices";
      ASSERT_EQ(dev.extra.size(), ref.extra.size());
      EXPECT_EQ(dev.extra.front().values, ref.extra.front().values) << "the same Scale per vertex";
      // Deterministic: a second run is bit-identical.
      const curvature::CurvatureField again = curvature::volume_estimate(
          c.mesh, c.volume, c.iso, volume_options_at(sigma, 0.1f, point), Device::default_device());
      EXPECT_EQ(again.H, dev.H);
      EXPECT_EQ(again.dcurv, dev.dcurv);
      EXPECT_EQ(again.surface_points, dev.surface_points);
    }
  }
}

// The sphere of radius R as a density (R - r, inside above) and as a level set (r - R, inside
// below) gives the same curvature, +1/R, and outward normals, either way.
TEST(VolumeEstimator, SphereSignsDensityAndLevelSet) {
  openvdb::initialize();
  const double R = 12;
  const Eigen::Vector3d c(16.3, 15.8, 16.1);
  for (volume::Inside inside : {volume::Inside::Above, volume::Inside::Below}) {
    const double s = inside == volume::Inside::Above ? 1 : -1;
    const volume::Volume v = sample_affine(
        [&](const Eigen::Vector3d& p) { return s * (R - (p - c).norm()); }, {33, 33, 33},
        Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), inside);
    const Mesh m = mc::extract(v, 0.0f, Device::default_device());
    ASSERT_GT(m.vertex_count(), 500u);
    const curvature::CurvatureField f = curvature::volume_estimate(
        m, v, 0.0f, volume_options_at(1.0, 1.0f), Device::default_device());
    double worst = 0;
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
      worst = std::max(worst, std::abs(f.H[i] * R - 1));
      const Eigen::Vector3d radial =
          (Eigen::Vector3d(m.positions[i][0], m.positions[i][1], m.positions[i][2]) - c)
              .normalized();
      ASSERT_GT(radial.dot(Eigen::Vector3d(f.normals[i][0], f.normals[i][1], f.normals[i][2])),
                0.999);
      ASSERT_GE(f.k1[i], f.k2[i]);
    }
    // Smoothing a distance field at sigma moves its zero set in by about sigma^2 / R.
    EXPECT_LT(worst, 0.02) << (inside == volume::Inside::Above ? "density" : "level set");
  }
}

// With the scale shrinking with the grid (one voxel), the error falls at second order: smoothing
// moves the isosurface by about sigma^2 times the field's Laplacian over its gradient, a relative
// change of the curvature of order (sigma k)^2.
TEST(VolumeEstimator, SecondOrderConvergence) {
  for (const char* name : {"torus", "ellipsoid"}) {
    double previous = 0;
    for (int res : {48, 96}) {
      const Case c = catalogue(name, res);
      const auto field = datasets::make_field(name);
      std::vector<double> H, K;
      exact(*field, c.mesh, H, K);
      const curvature::CurvatureField f = curvature::volume_estimate(
          c.mesh, c.volume, c.iso, volume_options_at(voxel_of(c.volume), 1.0f),
          Device::default_device());
      const Errors e = errors(f, H, K);
      if (previous > 0) {
        EXPECT_GT(previous / e.H, 3.0) << name << " " << res << ": " << e.H;
      }
      previous = e.H;
      // The torus's tube radius is 12 voxels at 96^3: (1/12)^2 = 0.7%.
      if (res == 96) {
        EXPECT_LT(e.H, 0.01) << name;
        EXPECT_LT(e.K, 0.02) << name;
      }
    }
  }
}

// An anisotropic grid (slices twice as thick) and a rotated one (direction matrix) of the same
// ellipsoid give its curvature as the isotropic grid does.
TEST(VolumeEstimator, AnisotropicAndRotatedGrids) {
  openvdb::initialize();
  const Eigen::Vector3d axes(20, 14, 11), c(32, 32, 32);
  auto ellipsoid = [&](const Eigen::Vector3d& p) {  // inside above 0, smooth
    const Eigen::Vector3d q = (p - c).cwiseQuotient(axes);
    return 1 - q.squaredNorm();
  };
  struct Grid {
    const char* name;
    Eigen::Vector3d spacing;
    Eigen::Matrix3d R;
    std::array<int, 3> dims;
  };
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Grid grids[] = {{"isotropic", {1, 1, 1}, Eigen::Matrix3d::Identity(), {65, 65, 65}},
                        {"anisotropic", {1, 1, 2}, Eigen::Matrix3d::Identity(), {65, 65, 33}},
                        {"rotated", {1, 1, 1}, rot, {90, 90, 90}}};
  double iso_error = 0;
  for (const Grid& g : grids) {
    // The rotated grid's box covers the ellipsoid: origin at the box centre minus half its span.
    const Eigen::Vector3d half =
        g.R * g.spacing.cwiseProduct(Eigen::Vector3d(g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1)) /
        2;
    const volume::Volume v =
        sample_affine(ellipsoid, g.dims, g.spacing, c - half, g.R, volume::Inside::Above);
    const Mesh m = mc::extract(v, 0.0f, Device::default_device());
    ASSERT_GT(m.vertex_count(), 1000u) << g.name;
    std::vector<double> H, K;
    for (const Vec3f& p : m.positions) {
      // Exact curvature of the ellipsoid at the nearest surface point along the gradient.
      Eigen::Vector3d q(p[0], p[1], p[2]);
      for (int k = 0; k < 50; ++k) {
        const Eigen::Vector3d gq = -2 * (q - c).cwiseQuotient(axes.cwiseProduct(axes));
        q -= ellipsoid(q) * gq / gq.squaredNorm();
      }
      const Eigen::Vector3d gq = -2 * (q - c).cwiseQuotient(axes.cwiseProduct(axes));
      const Eigen::Matrix3d Hs = (-2 * axes.cwiseProduct(axes).cwiseInverse()).asDiagonal();
      const Eigen::Vector3d n = -gq.normalized();
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
      const Eigen::Matrix3d S = -P * Hs * P / gq.norm();
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(S);
      // Eigenvalues: 0 (normal) and k1, k2; H = trace / 2, K = sum of pairwise products.
      const Eigen::Vector3d ev = es.eigenvalues();
      H.push_back(ev.sum() / 2);
      K.push_back(ev[0] * ev[1] + ev[1] * ev[2] + ev[0] * ev[2]);
    }
    const curvature::CurvatureField f = curvature::volume_estimate(
        m, v, 0.0f, volume_options_at(2.0, 1.0f), Device::default_device());
    const Errors e = errors(f, H, K);
    if (std::string(g.name) == "isotropic") iso_error = e.H;
    // Smoothing a quadric adds a constant (sigma^2 sum 1/a_i^2 = 0.063 here), so the smoothed
    // field's level set through a vertex is the ellipsoid itself: what is left is the
    // reconstruction's own error, the same small figure on every grid. (Measured at the
    // smoothed isosurface, as the estimator did before, the ellipsoid shrank by 3% and the
    // curvature was off by as much.)
    EXPECT_LT(e.H, 0.005) << g.name;
    EXPECT_LT(e.K, 0.01) << g.name;
    if (iso_error > 0) {
      EXPECT_NEAR(e.H, iso_error, 0.003) << g.name;
    }
  }
}

// A CT-like volume: a solid sphere whose edge is blurred over about a voxel, grey levels 20 and
// 220, Gaussian noise of 3 grey levels, rounded to uint8. The automatic scale grows above a voxel
// there and stays at its smallest (0.8 voxel) on the smooth float version; the targets
// hold.
volume::Volume ct_sphere(double R, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d c(24.2, 23.9, 24.1);
  return sample_affine(
      [&](const Eigen::Vector3d& p) {
        const double edge = 0.5 * std::erfc(((p - c).norm() - R) / std::sqrt(2.0));
        const double v = 20 + 200 * edge + noise * gauss(rng);
        return noise > 0 ? std::clamp(std::round(v), 0.0, 255.0) : v;
      },
      {49, 49, 49}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
      volume::Inside::Above, noise > 0 ? "uint8" : "float");
}

TEST(VolumeEstimator, CtLikeSphereAtAutoScale) {
  openvdb::initialize();
  const double R = 16;
  const volume::Volume noisy = ct_sphere(R, 3, 7), smooth = ct_sphere(R, 0, 7);
  const float iso = 120;
  const Mesh mn = mc::extract(noisy, iso, Device::default_device());
  const Mesh ms = mc::extract(smooth, iso, Device::default_device());
  const curvature::ScaleChoice cn = curvature::auto_scale(noisy, mn, iso);
  const curvature::ScaleChoice cs = curvature::auto_scale(smooth, ms, iso);
  EXPECT_NEAR(cn.measured_noise, 3.0, 1.0) << "the added noise is 3 grey levels";
  EXPECT_LT(cs.measured_noise, 0.3);
  EXPECT_GT(cn.scale, 1.5) << "noisy 8-bit data: a larger scale";
  EXPECT_EQ(cs.scale, curvature::kAutoMinVoxels) << "a smooth float field: the smallest scale";

  curvature::Options o;
  o.estimator = curvature::Estimator::volume;
  curvature::EstimatorReport report;
  const curvature::CurvatureField f =
      curvature::estimate_field(mn, {&noisy, iso}, &Device::default_device(), o, &report);
  EXPECT_EQ(report.estimator, "volume");
  EXPECT_EQ(report.parameters.front().first, "scale");
  EXPECT_DOUBLE_EQ(report.parameters.front().second, cn.scale);
  // The blurred sphere's iso surface lies where the erfc profile is 1/2: radius R.
  std::vector<double> H(mn.vertex_count(), 1 / R), K(mn.vertex_count(), 1 / (R * R));
  const Errors e = errors(f, H, K);
  EXPECT_LT(e.H, 0.05);
  EXPECT_LT(e.K, 0.10);
}

// A CT-like spherical shell 3 voxels thick (radii 14.5 and 17.5, edges blurred over 0.7 voxel,
// uint8 with noise): smoothed at 3 voxels its peak sinks below the isovalue, so every vertex
// misses its surface at that scale. With the finer-scale fallback (the default) the vertices are
// measured at 1.5 voxels instead, where the shell survives, and get the curvature of their own
// side (outer +1/r, inner -1/r, K = 1/r^2 on both); without it they are all Unreliable.
TEST(VolumeEstimator, ThinShellFallsBackToFinerScale) {
  openvdb::initialize();
  const double r_in = 14.5, r_out = 17.5, blur = 0.7;
  const Eigen::Vector3d c(24.2, 23.9, 24.1);
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const volume::Volume shell = sample_affine(
      [&](const Eigen::Vector3d& p) {
        const double r = (p - c).norm();
        const double in = 0.5 * std::erfc((r_in - r) / (std::sqrt(2.0) * blur));
        const double out = 0.5 * std::erfc((r - r_out) / (std::sqrt(2.0) * blur));
        return std::clamp(std::round(20 + 200 * (in + out - 1) + 2 * gauss(rng)), 0.0, 255.0);
      },
      {49, 49, 49}, Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(),
      volume::Inside::Above, "uint8");
  const float iso = 120;
  const Mesh m = mc::extract(shell, iso, Device::default_device());
  const std::size_t n = m.vertex_count();
  ASSERT_GT(n, 5000u);
  std::vector<double> H(n), K(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p(m.positions[i][0], m.positions[i][1], m.positions[i][2]);
    const double r = (p - c).norm();
    H[i] = (r > 0.5 * (r_in + r_out) ? 1 : -1) / r, K[i] = 1 / (r * r);
  }
  for (Device* d : {&Device::default_device(), static_cast<Device*>(nullptr)}) {
    const std::string path = d ? "device" : "reference";
    curvature::Options o;
    o.estimator = curvature::Estimator::volume;
    o.scale = 3.0;
    o.finer_scales = false;
    curvature::EstimatorReport off;
    curvature::estimate_field(m, {&shell, iso}, d, o, &off);
    EXPECT_GT(off.unreliable, n * 9 / 10) << path << ": the shell vanishes at 3 voxels";
    EXPECT_EQ(off.finer_scale, 0u) << path;

    o.finer_scales = true;
    curvature::EstimatorReport on;
    const curvature::CurvatureField f = curvature::estimate_field(m, {&shell, iso}, d, o, &on);
    EXPECT_LT(on.unreliable, n / 100) << path;
    EXPECT_GT(on.finer_scale, n * 9 / 10) << path;
    EXPECT_EQ(on.parameters.front().second, 3.0) << path << ": the reported scale is the asked one";
    const Errors e = errors(f, H, K);
    std::printf(
        "  %s: %zu vertices, %zu unreliable without the fallback; with it %zu at a finer "
        "scale, %zu unreliable, H RMS %.4f, K RMS %.4f\n",
        path.c_str(), n, off.unreliable, on.finer_scale, on.unreliable, e.H, e.K);
    EXPECT_LT(e.H, 0.06) << path;  // measured 0.027 and 0.052 (the noise at 1.5 voxels)
    EXPECT_LT(e.K, 0.12) << path;
  }
}

TEST(VolumeEstimator, BadInput) {
  const Case c = catalogue("sphere", 24);
  curvature::Options o;
  o.estimator = curvature::Estimator::volume;
  EXPECT_THROW(curvature::estimate_field(c.mesh, {}, &Device::default_device(), o), Error);
  // Not positive, not finite, larger than the volume, and under the 0.65 voxel the B-spline
  // reconstruction alone smooths by (volume::kMinScaleVoxels; the grid's voxels are 1 wide).
  const double voxel = c.volume.grid->voxelSize()[0];
  for (double bad : {-1.0, std::nan(""), 1e9, 0.6 * voxel}) {
    o.scale = bad;
    EXPECT_THROW(curvature::estimate_field(c.mesh, {&c.volume, c.iso}, nullptr, o), Error) << bad;
    EXPECT_THROW(
        curvature::estimate_field(c.mesh, {&c.volume, c.iso}, &Device::default_device(), o), Error)
        << bad;
  }
}

// Vertices where the reconstructed gradient vanishes (a triangle in the flat outside) get finite
// values and the Unreliable flag, and are counted.
TEST(VolumeEstimator, VanishingGradientIsUnreliable) {
  openvdb::initialize();
  const volume::Volume v = ct_sphere(8, 0, 1);
  Mesh m = mc::extract(v, 120.0f, Device::default_device());
  const std::uint32_t base = std::uint32_t(m.vertex_count());
  m.positions.push_back({2, 2, 2}), m.positions.push_back({3, 2, 2}),
      m.positions.push_back({2, 3, 2});
  m.triangles.push_back({base, base + 1, base + 2});
  for (Device* d : {&Device::default_device(), static_cast<Device*>(nullptr)}) {
    curvature::Options o;
    o.estimator = curvature::Estimator::volume;
    o.scale = 1.0;
    curvature::EstimatorReport r;
    const curvature::CurvatureField f = curvature::estimate_field(m, {&v, 120.0f}, d, o, &r);
    EXPECT_EQ(r.unreliable, 3u);
    for (std::uint32_t i = base; i < base + 3; ++i) {
      EXPECT_EQ(f.unreliable[i], 1);
      EXPECT_EQ(f.H[i], 0.0f);
      EXPECT_TRUE(std::isfinite(f.ao[i]));
      EXPECT_NEAR(std::abs(f.normals[i][2]), 1.0f, 1e-6f);
    }
    EXPECT_EQ(f.unreliable[0], 0);
  }
}

}  // namespace
}  // namespace isocurv::test
