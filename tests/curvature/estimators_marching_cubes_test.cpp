// The mesh estimators on a marching-cubes torus with volume-gradient normals, against the exact
// curvature (SEEDS-SPEC 3.2 (d), 4.2 (c)): what matters for isocurv's own meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "curvature/batagelo.h"
#include "curvature/cubic_fit.h"
#include "curvature/meyer.h"
#include "curvature/normal_sampling.h"
#include "curvature/prantl.h"
#include "curvature/quadric_fit.h"
#include "curvature/reference.h"
#include "datasets/exact_curvature.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "test_meshes.h"
#include "volume/gradient_normals.h"

namespace isocurv::test {
namespace {

using curvature::CurvatureField;

struct Percentiles {
  double p50, p90;
};

// The median and 90th percentile of |x - exact| / RMS(exact) over the vertices.
Percentiles scaled_error_percentiles(const std::vector<double>& x,
                                     const std::vector<double>& exact) {
  double ss = 0;
  for (double v : exact) ss += v * v;
  const double scale = std::sqrt(ss / double(exact.size()));
  std::vector<double> e;
  for (std::size_t i = 0; i < x.size(); ++i) e.push_back(std::abs(x[i] - exact[i]) / scale);
  std::sort(e.begin(), e.end());
  return {e[e.size() / 2], e[e.size() * 9 / 10]};
}

TEST(EstimatorsMarchingCubes, TorusWithVolumeNormals) {
  openvdb::initialize();
  const auto field = datasets::make_field("torus");
  const volume::Volume vol = datasets::sample(*field, 64);
  const Mesh m = mc::extract(vol, float(field->isovalue()), Device::default_device());
  const std::vector<Vec3f> n = volume::gradient_normals(vol, m.positions);
  std::vector<double> eh, ek;
  for (const Vec3f& p : m.positions) {
    const datasets::SurfaceCurvature c = datasets::exact_curvature(
        *field, datasets::project_to_surface(*field, Eigen::Vector3d(p[0], p[1], p[2])));
    eh.push_back(c.H), ek.push_back(c.K);
  }
  curvature::Options o;
  o.vertex_normals = &n;
  using Fn = std::function<CurvatureField()>;
  const std::vector<std::pair<std::string, Fn>> estimators = {
      {"rusinkiewicz", [&] { return curvature::estimate_reference(m, o); }},
      {"batagelo", [&] { return curvature::estimate_batagelo_reference(m, o); }},
      {"prantl3", [&] { return curvature::estimate_prantl_reference(m, o, 3); }},
      {"prantl2", [&] { return curvature::estimate_prantl_reference(m, o, 2); }},
      {"quadric", [&] { return curvature::estimate_quadric_fit_reference(m, o); }},
      {"cubic", [&] { return curvature::estimate_cubic_fit_reference(m, o); }},
      {"sampling", [&] { return curvature::estimate_normal_sampling_reference(m, o); }},
      {"meyer", [&] { return curvature::estimate_meyer_reference(m, o); }}};
  // Each estimator's accuracy bounds: relative RMS of H and K, and the median and 90th
  // percentile of |x - exact| / RMS(exact) (the per-vertex terms of the relative RMS), which
  // bound the bulk of the vertices where a few blow-ups make the RMS meaningless. The RMS bounds
  // are the estimators' known accuracy on this mesh (docs/curvature.md, "On marching-cubes
  // meshes", bench_estimators: rusinkiewicz 0.0125 / 0.0349, batagelo 0.0161 / 0.0267, prantl3
  // 0.0128 / 0.0358, cubic 0.028 / 0.033, meyer 0.38 / 0.47) with a 1.5x margin; the
  // percentile bounds are the values measured here (printed) with a 1.5x margin. quadric and
  // sampling sample normal curvatures from the positions alone (docs/curvature.md): they refuse
  // the vertices whose sample directions nearly lie on two lines (flagged, at most `flags`) and
  // leave out samples from tiny raised edges, so their errors are over the vertices they measure
  // (measured, H / K: quadric RMS 0.20 / 1.04, p50 0.041 / 0.075, p90 0.30 / 0.37, 272 flagged;
  // sampling RMS 1.3 / 25, p50 0.19 / 0.22, p90 1.6 / 3.9, 406 flagged); sampling's p90 is still
  // several times the curvature. meyer uses no normals
  // and sees marching cubes' irregular triangles (measured p50 0.11 / 0.18).
  struct Bound {
    double rms_h, rms_k, p50_h, p50_k, p90_h, p90_k;
    double flags = 0;  ///< the fraction of vertices an estimator may flag
  };
  const std::map<std::string, Bound> bounds = {
      {"rusinkiewicz", {0.019, 0.052, 0.0096, 0.019, 0.032, 0.090}},
      {"batagelo", {0.024, 0.040, 0.0098, 0.017, 0.041, 0.064}},
      {"prantl3", {0.019, 0.054, 0.0098, 0.020, 0.032, 0.089}},
      {"prantl2", {0.019, 0.055, 0.0098, 0.021, 0.032, 0.092}},
      {"quadric", {0.30, 1.6, 0.062, 0.11, 0.45, 0.55, 0.05}},
      {"cubic", {0.042, 0.050, 0.021, 0.020, 0.074, 0.082}},
      {"sampling", {2.0, 37, 0.28, 0.34, 2.5, 5.8, 0.07}},
      {"meyer", {0.57, 0.70, 0.17, 0.27, 0.96, 1.2}}};
  std::map<std::string, std::pair<double, double>> err;
  for (const auto& [name, fn] : estimators) {
    const CurvatureField f = fn();
    std::vector<double> h, k, mh, mk;  // over the vertices the estimator measured
    std::size_t flagged = 0;
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (!f.unreliable.empty() && f.unreliable[i]) {
        ++flagged;
        continue;
      }
      h.push_back(f.H[i]), k.push_back(f.K[i]), mh.push_back(eh[i]), mk.push_back(ek[i]);
    }
    err[name] = {relative_rms(h, mh), relative_rms(k, mk)};
    const Percentiles ph = scaled_error_percentiles(h, mh), pk = scaled_error_percentiles(k, mk);
    std::printf(
        "  torus 64^3 (%zu v) %-12s relative RMS H %.4f K %.4f, p50 H %.4f K %.4f, p90 H %.4f "
        "K %.4f, %zu unreliable\n",
        m.vertex_count(), name.c_str(), err[name].first, err[name].second, ph.p50, pk.p50,
        ph.p90, pk.p90, flagged);
    EXPECT_TRUE(all_finite(f)) << name;
    const Bound& b = bounds.at(name);
    EXPECT_LE(double(flagged), b.flags * double(f.size()))
        << name << ": every vertex of a closed, fine mesh can be measured (quadric, sampling: "
        << "but those whose samples lie on nearly two lines)";
    EXPECT_LT(err[name].first, b.rms_h) << name;
    EXPECT_LT(err[name].second, b.rms_k) << name;
    EXPECT_LT(ph.p50, b.p50_h) << name;
    EXPECT_LT(pk.p50, b.p50_k) << name;
    EXPECT_LT(ph.p90, b.p90_h) << name;
    EXPECT_LT(pk.p90, b.p90_k) << name;
  }
  const auto [rh, rk] = err["rusinkiewicz"];
  // Appendix A4 at 64^3 (vtkMarchingCubes, exact-gradient normals): Rusinkiewicz 0.0104 / 0.0327,
  // Batagelo 0.0134 / 0.0237, Prantl 3e 0.0094 / 0.0284.
  EXPECT_LT(err["batagelo"].second, rk);       // 3.2 (d): K no worse
  EXPECT_LT(err["prantl3"].first, 1.2 * rh);   // 4.2 (c): within 1.2x
  EXPECT_LT(err["prantl3"].second, 1.2 * rk);
  EXPECT_LT(rh, 0.02);
  EXPECT_LT(rk, 0.06);
}

}  // namespace
}  // namespace isocurv::test
