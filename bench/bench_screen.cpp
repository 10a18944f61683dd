// Screen-space curvature benchmark (SEEDS-SPEC 4.4 (d), the paper's Fig. 17-18): frame time
// against pixel coverage at 800x600 and 1920x1200 (zoomed so the surface covers ~2-100% of the
// image), split into the ray cast (G-buffer from the volume) and the estimate, for 2 and 3
// edges, LOD on and off, and Mellado's sphere fit. Beside it, from the same run and volume, the
// isovalue-slider update: re-cast + estimate at 800x600 against mc::Mesher::extract +
// curvature::estimate (the explorer's object-space path, rendering excluded on both sides).
// With --protocol, instead the paper's accuracy protocol (SEEDS-SPEC 4.4 (c), Prantl et al.
// Figs. 10-11; screen::pull_back): marching-cubes meshes of the dragon and the bunny and the
// triangulated f1 (15k vertices) fully in view, the camera pulled back in 10 steps, MSE of each
// screen-space estimator against the object-space 3-edge per-vertex curvature interpolated in
// the triangles. Not a test: prints tables.
//
//   bench_screen [--passes N] [--isovalues N] [--protocol] [--datasets DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/cl_device.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "datasets/field.h"
#include "datasets/heightfield_mesh.h"
#include "datasets/sample.h"
#include "mc/extract.h"
#include "screen/estimate.h"
#include "screen/pull_back.h"
#include "screen/ray_cast.h"
#include "volume/dense_field.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}
template <class F>
double median_ms(int passes, F&& f) {
  std::vector<double> t;
  for (int i = 0; i < passes; ++i) {
    const auto t0 = Clock::now();
    f();
    t.push_back(ms_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

/// The protocol on one mesh: per step, each estimator's MSE of H and K (relative, i.e. divided
/// by the mean square of the object-space values, in brackets absolute), the 2- vs 3-edge
/// difference and the Gaussian-to-mean MSE ratio of the 2-edge estimator.
void protocol(const std::string& name, const Mesh& mesh, Device& dev) {
  curvature::Options co;
  co.estimator = curvature::Estimator::prantl3;
  const curvature::CurvatureField object = curvature::estimate(mesh, dev, co);
  std::vector<screen::ScreenOptions> est(5);
  est[1].edges = 3;
  est[2].lod = true;
  est[3].edges = 3, est[3].lod = true;
  est[4].estimator = screen::ScreenEstimator::mellado;
  const screen::PullBackOptions po;  // 1024x768, 10 steps of 0.5 x the fitting distance
  const auto t0 = Clock::now();
  const auto steps = screen::pull_back(mesh, object, est, &dev, po);
  std::printf("\n== %s: %zu vertices, %zu triangles, %dx%d, %.1f s\n", name.c_str(),
              mesh.positions.size(), mesh.triangles.size(), po.width, po.height,
              ms_since(t0) / 1000);
  std::printf("%5s %6s | %-19s | %-19s | %-19s | %-9s | %7s %7s | %6s\n", "dist", "cover%",
              "2-edge rel H   K", "3-edge rel H   K", "2e+LOD rel H   K", "Mellado H", "2v3 H%",
              "2v3 K%", "K/H");
  for (const auto& st : steps) {
    const auto& e = st.errors;
    auto pct = [](double a, double b) { return b > 0 ? 100 * std::abs(a - b) / b : 0.0; };
    std::printf(
        "%5.1f %6.2f | %9.3g %9.3g | %9.3g %9.3g | %9.3g %9.3g | %9.3g | %7.2f %7.2f | %6.2f\n",
        st.distance, 100 * st.coverage, e[0].rel_H, e[0].rel_K, e[1].rel_H, e[1].rel_K, e[2].rel_H,
        e[2].rel_K, e[4].rel_H, pct(e[1].mse_H, e[0].mse_H), pct(e[1].mse_K, e[0].mse_K),
        e[0].mse_H > 0 ? e[0].mse_K / e[0].mse_H : 0.0);
  }
  std::printf(
      "(3e+LOD rel H, K at the nearest step: %.3g %.3g; absolute MSE H, K of 2 edges "
      "there: %.3g %.3g)\n",
      steps.front().errors[3].rel_H, steps.front().errors[3].rel_K, steps.front().errors[0].mse_H,
      steps.front().errors[0].mse_K);
}

int run_protocol(const std::string& root, Device& dev) {
  std::printf(
      "The paper's protocol: screen space against object-space 3-edge curvature "
      "(prantl3) interpolated in the triangles; paper: 2 and 3 edges within 2%%, "
      "Gaussian MSE roughly double the mean's.\n");
  for (auto [name, path] : {std::pair<std::string, std::string>{
                                "dragon 256 (aa)", root + "/aa_dragon/dragon-256-aa-l0_1.vol"},
                            {"bunny 256 (vg)", root + "/vg_bunny/bunny-256.vol"}}) {
    const volume::Volume v = volume::load(path);
    protocol(name, mc::extract(v, float(v.stats.suggested_isovalue), dev), dev);
  }
  protocol("f1 15k (122^2 grid)", datasets::heightfield_mesh(*datasets::make_field("f1"), 122),
           dev);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // rows as they come, also into a file
  int passes = 3, n_iso = 10;
  bool protocol_only = false;
  std::string root = ISOCURV_SHARED_DATASETS;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--protocol"))
      protocol_only = true;
    else if (!std::strcmp(argv[i], "--datasets") && i + 1 < argc)
      root = argv[++i];
    else if (!std::strcmp(argv[i], "--passes") && i + 1 < argc)
      passes = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--isovalues") && i + 1 < argc)
      n_iso = std::max(2, std::atoi(argv[++i]));
  }
  Device& dev = Device::default_device();
  std::printf("device: %s (%s)\n", dev.info().name.c_str(), dev.info().type.c_str());
  if (protocol_only) return run_protocol(root, dev);
  for (const char* name : {"torus", "gyroid", "buckyball"}) {
    const auto field = datasets::make_field(name);
    const volume::Volume v = datasets::sample(*field, 128);
    const volume::DenseField cv(v);
    const float iso = float(field->isovalue());
    std::printf("\n== %s 128^3, isovalue %g\n", name, iso);
    std::printf("%-10s %5s %8s %8s %8s %8s %8s %8s %8s %8s\n", "size", "zoom", "cover%", "cast",
                "plain", "speedup", "2e", "3e", "2e+LOD", "Mellado");
    screen::ScreenOptions o2, o3, ol, om;
    o3.edges = 3;
    ol.lod = true;
    om.estimator = screen::ScreenEstimator::mellado;
    for (auto [w, h] : {std::pair{800, 600}, std::pair{1920, 1200}})
      for (double zoom : {0.15, 0.35, 0.7, 1.2, 2.5, 5.0}) {
        ViewSpec spec;
        spec.zoom = zoom;
        const screen::ViewFrame f =
            screen::view_frame(fit_camera(cv.bounds, spec, double(w) / h), w, h);
        screen::GBuffer g = screen::ray_cast(cv, iso, f, dev);  // warm-up (program build)
        // The default (safe stride, 8 bisections, secant) against the plain march (0.5-voxel
        // steps, 16 bisections), pass by pass alternating so load affects both alike.
        screen::CastOptions plain;
        plain.safe_stride = false, plain.secant = false, plain.bisections = 16;
        std::vector<double> tc, tp;
        for (int p = 0; p < passes; ++p) {
          tc.push_back(median_ms(1, [&] { g = screen::ray_cast(cv, iso, f, dev); }));
          tp.push_back(median_ms(1, [&] { screen::ray_cast(cv, iso, f, dev, plain); }));
        }
        std::sort(tc.begin(), tc.end()), std::sort(tp.begin(), tp.end());
        const double cast = tc[tc.size() / 2], cast_plain = tp[tp.size() / 2];
        double t[4];
        int k = 0;
        for (const auto* o : {&o2, &o3, &ol, &om}) {
          screen::estimate(g, dev, *o);
          t[k++] = median_ms(passes, [&] { screen::estimate(g, dev, *o); });
        }
        std::printf("%4dx%-5d %5.2f %8.1f %8.1f %8.1f %7.2fx %8.1f %8.1f %8.1f %8.1f\n", w, h, zoom,
                    100.0 * g.valid_count() / g.pixels(), cast, cast_plain, cast_plain / cast, t[0],
                    t[1], t[2], t[3]);
      }
    // The slider update, both paths, over n_iso isovalues across the value range.
    std::vector<float> isos;
    for (int i = 0; i < n_iso; ++i)
      isos.push_back(
          float(v.stats.min + (v.stats.max - v.stats.min) * (0.05 + 0.9 * i / (n_iso - 1))));
    const screen::ViewFrame f =
        screen::view_frame(fit_camera(cv.bounds, ViewSpec{}, 800.0 / 600), 800, 600);
    mc::Mesher mesher(v, dev);
    std::vector<double> screen_ms, object_ms;
    for (float is : isos) {
      screen::estimate(screen::ray_cast(cv, is, f, dev), dev, o2);
      screen_ms.push_back(
          median_ms(passes, [&] { screen::estimate(screen::ray_cast(cv, is, f, dev), dev, o2); }));
      object_ms.push_back(median_ms(passes, [&] {
        Mesh mesh = mesher.extract(is);
        curvature::Options co;
        co.ao_scale = curvature::default_ao_scale(mesh);
        curvature::estimate(mesh, dev, co);
      }));
    }
    auto med = [](std::vector<double> x) {
      std::sort(x.begin(), x.end());
      return x[x.size() / 2];
    };
    std::printf(
        "slider update (median over %d isovalues): screen space (cast + 2-edge estimate, "
        "800x600) %.1f ms = %.1f/s; extract + curvature %.1f ms = %.1f/s; ratio %.2fx\n",
        n_iso, med(screen_ms), 1000 / med(screen_ms), med(object_ms), 1000 / med(object_ms),
        med(object_ms) / med(screen_ms));
  }
  return 0;
}
