// measure::object_measures on volumes, as the app measures them: the surface extracted by the
// device mesher (app/pipeline.cpp extract_surface, default snap), the curvature of the default
// estimator (curvature::estimate_field, the volume's own at the automatic scale; the smoothed
// isosurface's points on binary masks), then the measures. Solids with known measures (sphere,
// torus, a rounded box with a spherical cavity) and one with two handles, each as a float level
// set, CT-like 8-bit (erfc edge, noise), binary masks 0/1 and 0/255, and on an anisotropic grid
// (spacing 1, 1, 2.5).
//
// The bounds (issue 43), the same for every class: area 0.5%, volume 0.2%, integral of H 1%,
// the Euler characteristic exact, the Gauss-Bonnet gap 1%; the few allowances beyond them are
// justified where they are made (Allowance). They are the targets, not the measured
// figures with a margin (ISOCURV_MEASURE_PRINT=1 prints those): most sit well inside (float and
// masks within 0.35% of area and 0.15% of volume against the mask's solid, CT within 0.25% of
// area and 0.04% of volume), the thick-slice masks' Gauss-Bonnet gaps nearest the bounds.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>

#include "core/cl_device.h"
#include "curvature/estimator.h"
#include "mc/extract.h"
#include "measure/object_measures.h"
#include "volume/from_dense.h"

namespace isocurv::measure {
namespace {

using Sdf = std::function<double(const Eigen::Vector3d&)>;  // signed distance, > 0 inside

/// What a class samples: the signed distance itself (float), an 8-bit CT-like edge
/// (20 + 200 erfc(-d / sqrt 2) / 2 + noise of deviation 4: blur one voxel, iso 120), or a mask.
enum class Kind { float_sdf, ct_u8, binary01, binary255 };

const char* name_of(Kind k) {
  switch (k) {
    case Kind::float_sdf: return "float";
    case Kind::ct_u8: return "ct_u8";
    case Kind::binary01: return "binary01";
    case Kind::binary255: return "binary255";
  }
  return "?";
}

struct Sampled {
  volume::Volume volume;
  float iso = 0;
  double mask_volume = 0;  ///< the voxels whose centre is inside, times the voxel's volume
};

/// `sdf` sampled at world = lo + spacing * index over the box [lo, hi].
Sampled sample(const Sdf& sdf, Kind kind, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
               const Eigen::Vector3d& spacing = Eigen::Vector3d(1, 1, 1)) {
  std::array<int, 3> dims;
  for (int a = 0; a < 3; ++a) dims[a] = int(std::ceil((hi[a] - lo[a]) / spacing[a])) + 1;
  std::vector<float> data(std::size_t(dims[0]) * dims[1] * dims[2]);
  std::mt19937 rng(43);
  std::normal_distribution<double> noise(0.0, 4.0);
  std::size_t i = 0, inside = 0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const double d = sdf(lo + spacing.cwiseProduct(Eigen::Vector3d(x, y, z)));
        double v = d;
        inside += d > 0;
        if (kind == Kind::ct_u8)
          v = std::clamp(std::round(20 + 100 * std::erfc(-d / std::sqrt(2.0)) + noise(rng)), 0.0,
                         255.0);
        else if (kind == Kind::binary01)
          v = d > 0;
        else if (kind == Kind::binary255)
          v = d > 0 ? 255 : 0;
        data[i++] = float(v);
      }
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  for (int a = 0; a < 3; ++a) m(a, a) = spacing[a], m(3, a) = lo[a];
  volume::DenseSource src;
  src.path = "test";
  src.format = "generated";
  src.voxel_type = kind == Kind::float_sdf ? "float" : "uint8";
  src.inside = volume::Inside::Above;
  Sampled s;
  s.mask_volume = double(inside) * spacing.prod();
  s.volume = volume::from_dense(data.data(), dims,
                                openvdb::math::Transform::createLinearTransform(m), src);
  s.iso = kind == Kind::float_sdf ? 0.0f
          : kind == Kind::ct_u8   ? 120.0f
          : kind == Kind::binary01 ? 0.5f
                                   : 127.5f;
  return s;
}

/// The app's measure of a volume: extract (device mesher, default options), the default volume
/// estimator, object_measures.
std::vector<ObjectMeasures> measure_volume(const Sampled& s) {
  openvdb::initialize();
  Device& device = Device::default_device();
  mc::Options mo;
  mo.snap = mc::kDefaultSnap;
  const Mesh mesh = mc::extract(s.volume, s.iso, device, mo);
  curvature::Options co;
  co.estimator = curvature::Estimator::volume;
  curvature::EstimatorReport report;
  const curvature::CurvatureField field =
      curvature::estimate_field(mesh, {&s.volume, s.iso}, &device, co, &report);
  if (std::getenv("ISOCURV_MEASURE_PRINT"))
    for (const auto& [key, value] : report.parameters)
      if (key == "scale_voxels") std::printf("  scale %.2f voxels, %zu finer\n", value, report.finer_scale);
  if (std::getenv("ISOCURV_MEASURE_PRINT"))
    for (const auto& x : field.extra)
      if (x.name == "Scale") {
        std::vector<float> v = x.values;
        std::sort(v.begin(), v.end());
        std::printf("  per-vertex scale p5 %.3f p50 %.3f p95 %.3f\n", v[v.size() / 20], v[v.size() / 2], v[v.size() * 19 / 20]);
      }
  return object_measures(mesh, field);
}

struct Expected {
  double area = 0, volume = 0, integral_H = 0;
  long long euler = 2;
};

constexpr double kArea = 0.005, kVolume = 0.002, kIntegralH = 0.01, kGap = 0.01;

double rel(double x, double exact) { return x / exact - 1; }

void print(const std::string& what, const ObjectMeasures& m, const Expected& e) {
  if (!std::getenv("ISOCURV_MEASURE_PRINT")) return;
  std::printf("%-28s area %+.3f%%  volume %+.3f%%  int H %+.3f%%  chi %lld  GB %+.3f%%\n",
              what.c_str(), 100 * rel(m.area, e.area), 100 * rel(m.volume, e.volume),
              100 * rel(m.integral_H, e.integral_H), m.euler, 100 * m.gauss_bonnet_gap());
}

/// Per-class allowances beyond the bounds, each justified where it is used.
struct Allowance {
  double volume = kVolume, gap = kGap;
};

/// The total over all components against `e`, within the bounds. A binary mask is
/// compared with the solid that has the mask's own volume (its inside voxel centres): the two
/// differ from the solid's by the lattice-point count's error (the torus below: +0.58%, at other
/// grid offsets from -0.47% to +0.52%), which no reconstruction from the mask can see past. That
/// solid is taken as the parallel body at distance t = (mask volume - volume) / area, whose
/// measures Steiner's formula gives: area + 2 t int H, int H + 2 pi chi t. The exact volume is
/// asserted too, within the count's error.
ObjectMeasures check(const std::string& what, const std::vector<ObjectMeasures>& objects,
                     const Expected& e, const Sampled& s, Kind kind, Allowance allow = {}) {
  const ObjectMeasures t = total(objects);
  print(what, t, e);
  const bool binary = kind == Kind::binary01 || kind == Kind::binary255;
  Expected ref = e;
  if (binary) {
    const double offset = (s.mask_volume - e.volume) / e.area;
    ref.volume = s.mask_volume;
    ref.area = e.area + 2 * offset * e.integral_H;
    ref.integral_H = e.integral_H + 2 * M_PI * double(e.euler) * offset;
    if (std::getenv("ISOCURV_MEASURE_PRINT")) print("  against the mask's solid", t, ref);
    EXPECT_NEAR(rel(t.volume, e.volume), 0, 0.02) << what;
  }
  EXPECT_TRUE(t.closed) << what;
  EXPECT_EQ(t.euler, e.euler) << what;
  EXPECT_NEAR(rel(t.area, ref.area), 0, kArea) << what;
  EXPECT_NEAR(rel(t.volume, ref.volume), 0, allow.volume) << what;
  EXPECT_NEAR(rel(t.integral_H, ref.integral_H), 0, kIntegralH) << what;
  EXPECT_NEAR(t.gauss_bonnet_gap(), 0, allow.gap) << what;
  return t;
}

constexpr Kind kAllKinds[] = {Kind::float_sdf, Kind::ct_u8, Kind::binary01, Kind::binary255};

// A sphere of radius 12 voxels: area 4 pi R^2, volume 4/3 pi R^3, integral of H 4 pi R.
TEST(MeasureAccuracy, Sphere) {
  const double R = 12;
  const Sdf sdf = [&](const Eigen::Vector3d& p) { return R - p.norm(); };
  const Expected e{4 * M_PI * R * R, 4 * M_PI * R * R * R / 3, 4 * M_PI * R, 2};
  const Eigen::Vector3d lo(-16.3, -16.1, -15.8), hi(16, 16, 16);  // off-centre on the grid
  for (Kind k : kAllKinds) {
    const Sampled v = sample(sdf, k, lo, hi);
    const auto objects = measure_volume(v);
    ASSERT_EQ(objects.size(), 1u) << name_of(k);
    check(std::string("sphere ") + name_of(k), objects, e, v, k);
  }
}

// A torus of radii 14 and 6: area 4 pi^2 R r, volume 2 pi^2 R r^2, integral of H 2 pi^2 R
// (the r terms cancel), Euler characteristic 0 (the gap is then relative to 2 pi).
TEST(MeasureAccuracy, Torus) {
  const double R = 14, r = 6;
  const Sdf sdf = [&](const Eigen::Vector3d& p) {
    const double q = std::hypot(p.x(), p.y()) - R;
    return r - std::hypot(q, p.z());
  };
  const Expected e{4 * M_PI * M_PI * R * r, 2 * M_PI * M_PI * R * r * r, 2 * M_PI * M_PI * R, 0};
  const Eigen::Vector3d lo(-23.2, -23.4, -9.7), hi(23, 23, 9.5);
  for (Kind k : kAllKinds) {
    const Sampled v = sample(sdf, k, lo, hi);
    const auto objects = measure_volume(v);
    ASSERT_EQ(objects.size(), 1u) << name_of(k);
    check(std::string("torus ") + name_of(k), objects, e, v, k);
  }
}

// A rounded box (the box of half-sizes h grown by a ball of radius rho; Steiner's formula gives
// its measures) with a spherical cavity of radius Rc: two surfaces, chi 2 + 2, the cavity's
// surface facing inward (negative volume and integral of H). Rotated, so that no face lies along
// the grid (a mask cannot place a face parallel to the grid within its voxel).
TEST(MeasureAccuracy, BoxWithSphericalCavity) {
  const Eigen::Matrix3d rot =
      (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  const Eigen::Vector3d h(9, 7, 5);
  const double rho = 7, Rc = 6;
  const Sdf sdf = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = (rot.transpose() * p).cwiseAbs() - h;
    const double box = rho - (q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0));
    return std::min(box, p.norm() - Rc);
  };
  const Eigen::Vector3d L = 2 * h;
  const double sumL = L.sum();
  const double S = 2 * (L.x() * L.y() + L.y() * L.z() + L.x() * L.z());  // the box's area
  const double box_area = S + 2 * M_PI * sumL * rho + 4 * M_PI * rho * rho;
  const double outer_volume =
      L.prod() + S * rho + M_PI * sumL * rho * rho + 4 * M_PI * rho * rho * rho / 3;
  const double outer_H = M_PI * sumL + 4 * M_PI * rho;
  const double cavity_volume = 4 * M_PI * Rc * Rc * Rc / 3;
  const Expected e{box_area + 4 * M_PI * Rc * Rc, outer_volume - cavity_volume,
                   outer_H - 4 * M_PI * Rc, 4};
  const Eigen::Vector3d lo(-21.3, -21.2, -20.1), hi(21, 21, 20);
  for (Kind k : kAllKinds) {
    const Sampled v = sample(sdf, k, lo, hi);
    const auto objects = measure_volume(v);
    ASSERT_EQ(objects.size(), 2u) << name_of(k);
    check(std::string("box with cavity ") + name_of(k), objects, e, v, k);
    // The cavity: the smaller surface, facing inward.
    const ObjectMeasures& cavity = objects[1];
    if (std::getenv("ISOCURV_MEASURE_PRINT"))
      std::printf("  cavity: area %+.3f%% volume %+.3f%% int H %+.3f%% GB %+.3f%%; outer GB %+.3f%%\n",
                  100 * rel(cavity.area, 4 * M_PI * Rc * Rc), 100 * rel(cavity.volume, -cavity_volume),
                  100 * rel(cavity.integral_H, -4 * M_PI * Rc), 100 * cavity.gauss_bonnet_gap(),
                  100 * objects[0].gauss_bonnet_gap());
    // Its radius is 3 binary scales (2 voxels): the shrinkage's fit is within 0.005 sigma there
    // (curvature::kSurfaceY1, kSurfaceY2), 0.25% of the volume, hence twice the volume bound. A mask's
    // cavity is compared with the mask's own (its lattice count is -0.53% off here) and the area
    // of the sphere of that volume.
    const bool binary = k == Kind::binary01 || k == Kind::binary255;
    const double cavity_ref =
        binary ? sample([&](const Eigen::Vector3d& p) { return Rc - p.norm(); }, k, lo, hi).mask_volume
               : cavity_volume;
    const double area_ref = 4 * M_PI * std::pow(3 * cavity_ref / (4 * M_PI), 2.0 / 3.0);
    EXPECT_EQ(cavity.euler, 2);
    EXPECT_NEAR(rel(cavity.volume, -cavity_ref), 0, kVolume * 2) << name_of(k);
    EXPECT_NEAR(rel(cavity.integral_H, -4 * M_PI * Rc), 0, kIntegralH) << name_of(k);
    EXPECT_NEAR(rel(cavity.area, area_ref), 0, kArea) << name_of(k);
    EXPECT_NEAR(cavity.gauss_bonnet_gap(), 0, kGap) << name_of(k);
  }
}

// A solid with two handles (chi -2): the smooth union (blend width 6) of two tori of radii 14
// and 6 whose rings overlap. Its measures are not known in closed form: every class is compared with the float
// grid's (the bounds are then on the difference, as the classes' errors against exact solids
// above are of either sign), and Gauss-Bonnet checks the curvature.
TEST(MeasureAccuracy, TwoHandles) {
  const double R = 14, r = 6, a = 11, k = 6;
  const auto torus = [&](const Eigen::Vector3d& p, double cx) {
    return r - std::hypot(std::hypot(p.x() - cx, p.y()) - R, p.z());
  };
  const Sdf sdf = [&](const Eigen::Vector3d& p) {
    const double d1 = torus(p, -a), d2 = torus(p, a);
    const double h = std::max(k - std::abs(d1 - d2), 0.0);
    return std::max(d1, d2) + h * h / (4 * k);  // smooth union of the interiors
  };
  const Eigen::Vector3d lo(-34.4, -23.3, -9.6), hi(34, 23, 9.5);
  const Sampled fv = sample(sdf, Kind::float_sdf, lo, hi);
  const auto reference = measure_volume(fv);
  ASSERT_EQ(reference.size(), 1u);
  const ObjectMeasures f = reference[0];
  EXPECT_EQ(f.euler, -2);
  EXPECT_EQ(f.genus(), 2);
  EXPECT_NEAR(f.gauss_bonnet_gap(), 0, kGap);
  const Expected e{f.area, f.volume, f.integral_H, -2};
  print("two handles float (ref.)", f, e);
  for (Kind kind : {Kind::ct_u8, Kind::binary01, Kind::binary255}) {
    const Sampled v = sample(sdf, kind, lo, hi);
    const auto objects = measure_volume(v);
    ASSERT_EQ(objects.size(), 1u) << name_of(kind);
    // A mask's volume against its own (check()); here the float grid's volume stands for exact.
    check(std::string("two handles ") + name_of(kind), objects, e, v, kind);
  }
  for (Kind kind : {Kind::float_sdf, Kind::binary01}) {
    const Sampled v = sample(sdf, kind, lo, hi, Eigen::Vector3d(1, 1, 2.5));
    const auto objects = measure_volume(v);
    ASSERT_EQ(objects.size(), 1u) << name_of(kind);
    // The mask on thick slices: the binary scale (2 voxels of the mean spacing, 2.7 units) is
    // 0.45 of the tube radius and the blend's saddles are 1.2 slices across: GB +2.0%. Allowed 3%.
    Allowance allow;
    if (kind == Kind::binary01) allow.gap = 0.03;
    check(std::string("two handles 1x1x2.5 ") + name_of(kind), objects, e, v, kind, allow);
  }
}

// The sphere and the torus on an anisotropic grid (spacing 1, 1, 2.5: thick slices), as float
// level sets and masks, against their exact measures with the same bounds.
TEST(MeasureAccuracy, AnisotropicGrid) {
  const Eigen::Vector3d spacing(1, 1, 2.5);
  const double Rs = 12, R = 14, r = 6;
  const Sdf sphere = [&](const Eigen::Vector3d& p) { return Rs - p.norm(); };
  const Sdf torus = [&](const Eigen::Vector3d& p) {
    return r - std::hypot(std::hypot(p.x(), p.y()) - R, p.z());
  };
  const Expected es{4 * M_PI * Rs * Rs, 4 * M_PI * Rs * Rs * Rs / 3, 4 * M_PI * Rs, 2};
  const Expected et{4 * M_PI * M_PI * R * r, 2 * M_PI * M_PI * R * r * r, 2 * M_PI * M_PI * R, 0};
  for (Kind k : {Kind::float_sdf, Kind::binary01, Kind::binary255}) {
    const Sampled vs = sample(sphere, k, {-16.3, -16.1, -17.8}, {16, 16, 18}, spacing);
    check(std::string("sphere 1x1x2.5 ") + name_of(k), measure_volume(vs), es, vs, k);
    const Sampled vt = sample(torus, k, {-23.2, -23.4, -11.7}, {23, 23, 12}, spacing);
    // The mask's torus: the binary scale (2.7 units) is 0.45 of the tube radius, past the range
    // where the shrinkage's fit holds (curvature::kSurfaceY1, to 1/2): the volume is 0.23% short
    // of the mask's. Allowed 0.3%.
    // Its Gauss-Bonnet gap, +1.03%, has the same cause: allowed 1.5%.
    Allowance allow;
    if (k != Kind::float_sdf) allow.volume = 0.003, allow.gap = 0.015;
    check(std::string("torus 1x1x2.5 ") + name_of(k), measure_volume(vt), et, vt, k, allow);
  }
}

}  // namespace
}  // namespace isocurv::measure

namespace isocurv::measure {
namespace {

// A binary mask with a ball and three specks of one voxel: the specks are below the binary scale
// (2 voxels), their smoothed field never reaches the half level, and the surface points would
// scatter them (before kMaxSurfaceChange, the frog's one-voxel labels came out with negative
// volumes). They are measured over their own vertices: a voxel's marching-cubes octahedron of
// volume 1/6, and the ball is still measured over its surface points.
TEST(MeasureAccuracy, SpecksBelowTheScaleKeepTheirOwnVertices) {
  const Sdf ball_and_specks = [](const Eigen::Vector3d& p) {
    const double ball = 8 - (p - Eigen::Vector3d(14, 16, 16)).norm();
    double specks = -1;
    for (const Eigen::Vector3d& c : {Eigen::Vector3d(28, 6, 6), Eigen::Vector3d(28, 26, 6), Eigen::Vector3d(28, 16, 27)})
      specks = std::max(specks, 0.4 - (p - c).cwiseAbs().maxCoeff());
    return std::max(ball, specks);
  };
  const Sampled s = sample(ball_and_specks, Kind::binary01, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(33, 33, 33));
  const std::vector<ObjectMeasures> objects = measure_volume(s);
  ASSERT_EQ(objects.size(), 4u);
  EXPECT_FALSE(objects[0].on_vertices);
  EXPECT_NEAR(objects[0].volume, 4.0 / 3 * 3.14159265358979 * 512, 0.02 * 4.0 / 3 * 3.14159265358979 * 512);
  for (std::size_t i = 1; i < 4; ++i) {
    EXPECT_TRUE(objects[i].on_vertices) << i;
    EXPECT_TRUE(objects[i].closed) << i;
    EXPECT_EQ(objects[i].euler, 2) << i;
    // Between the flat octahedron's 1/6 and the ball through its six vertices (0.52), where the
    // patches over its radial normals take it.
    EXPECT_GT(objects[i].volume, 1.0 / 6) << i;
    EXPECT_LT(objects[i].volume, 0.52) << i;
  }
  EXPECT_TRUE(total(objects).on_vertices);
}

}  // namespace
}  // namespace isocurv::measure
