// Line-extraction benchmark: the OpenCL feature lines (PoCL here) beside the
// curvature estimate that feeds them, in the same run, on marching-cubes meshes
// (Griffin et al. Table 1: lines add about 1% to the frame on the GPU; the
// issue asks for at most a quarter of the curvature time). Not a test: prints a
// table.
//
//   bench_lines [--quick] [--runs N]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/estimate.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "lines/extract.h"
#include "lines/polylines.h"
#include "lines/reference.h"
#include "lines/visibility.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

Camera camera_for(const Mesh& m) {
  std::array<double, 6> b = {1e30, -1e30, 1e30, -1e30, 1e30, -1e30};
  for (const Vec3f& p : m.positions)
    for (int c = 0; c < 3; ++c)
      b[2 * c] = std::min(b[2 * c], double(p[c])),
            b[2 * c + 1] = std::max(b[2 * c + 1], double(p[c]));
  return fit_camera(b, ViewSpec{}, 4.0 / 3.0);
}

void run_case(const std::string& name, const Mesh& mesh, int runs) {
  Device& dev = Device::default_device();
  curvature::CurvatureField field;
  curvature::estimate(mesh, dev, {}, field);
  const Camera cam = camera_for(mesh);
  lines::Options cs, all;
  all.lines = lines::parse_line_selection("all");
  lines::Segments segs;
  auto curv = [&] { curvature::estimate(mesh, dev, {}, field); };
  auto contours = [&] { segs = lines::extract(mesh, field, cam, cs, dev); };
  // the explorer's case: the camera moved, the mesh is already on the device
  auto moved = [&] { segs = lines::extract(mesh, field, cam, cs, dev, nullptr, false); };
  auto every = [&] { segs = lines::extract(mesh, field, cam, all, dev); };
  const std::vector<double> t =
      bench::medians_ms({{curv, runs}, {contours, runs}, {moved, runs}, {every, runs}});
  segs = lines::extract(mesh, field, cam, cs, dev);
  const std::size_t n_cs = segs.size();
  auto t0 = std::chrono::steady_clock::now();
  const lines::Polylines joined = lines::join_segments(segs);
  const double t_join =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  lines::Segments ref;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    ref = lines::extract_reference(mesh, field, cam, cs);
  }
  const double t_ref =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  lines::VisibilityTester vis(mesh);
  const double t_locator =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  const std::vector<bool> visible = vis.visible_segments(segs, cam);
  const double t_vis =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // The steps: each one's median over `runs` timed calls (a single call is too noisy).
  std::vector<lines::Timings> calls(std::max(1, runs));
  for (lines::Timings& c : calls) lines::extract(mesh, field, cam, cs, dev, &c);
  auto median = [&](double lines::Timings::*step) {
    std::vector<double> v;
    for (const lines::Timings& c : calls) v.push_back(c.*step);
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  lines::Timings steps;
  for (double lines::Timings::*step :
       {&lines::Timings::checks, &lines::Timings::upload, &lines::Timings::ring,
        &lines::Timings::view, &lines::Timings::count, &lines::Timings::emit})
    steps.*step = median(step);
  std::size_t n_visible = 0;
  for (bool v : visible) n_visible += v;
  std::printf(
      "%-20s %9zu %8.1f | %7.1f %6.3f %7.1f %6.3f %7.1f %6.3f | %7zu "
      "%6.1f %7.1f | %6.0f %6.0f %6zu"
      " | %6.1f %6.1f %6.1f %6.1f %6.1f %6.1f\n",
      name.c_str(), mesh.positions.size(), t[0], t[1], t[1] / t[0], t[2], t[2] / t[0], t[3],
      t[3] / t[0], n_cs, t_join, t_ref, t_locator, t_vis, n_visible, steps.checks, steps.upload,
      steps.ring, steps.view, steps.count, steps.emit);
  std::fflush(stdout);
  (void)joined;
}

Mesh mesh_of(const volume::Volume& v, float iso) {
  return mc::extract(v, iso, Device::default_device());
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  bool quick = false;
  int runs = 7;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
      runs = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_lines [--quick] [--runs N]\n");
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  openvdb::initialize();
  std::printf(
      "device: %s; medians of %d runs; iso view; 'c+s' = contours and "
      "suggestive contours,\n"
      "'moved' = the same with the mesh already on the device "
      "(explorer camera move), 'all' = all four\n"
      "types; ratios are to the curvature estimate of the same run. "
      "Join, reference (1 thread), locator\n"
      "build and ray-cast visibility (SVG) once each; then the steps "
      "of a c+s call (medians; queue drained between).\n",
      Device::default_device().info().name.c_str(), runs);
  std::printf(
      "%-20s %9s %8s | %7s %6s %7s %6s %7s %6s | %7s %6s %7s | %6s %6s "
      "%6s | %6s %6s %6s %6s %6s %6s\n",
      "mesh", "vertices", "curv ms", "c+s ms", "/curv", "moved", "/curv", "all ms", "/curv", "segs",
      "join", "ref ms", "locate", "rays", "vis", "checks", "upload", "ring", "view", "count",
      "emit");
  auto sphere = datasets::make_field("sphere");
  run_case("sphere 256^3", mesh_of(datasets::sample(*sphere, 256), float(sphere->isovalue())),
           runs);
  if (quick) return 0;
  const std::string flower =
      std::string(ISOCURV_SHARED_DATASETS) + "/aa_octaflower/octa-flower17k-512-aa-l0_1.vol";
  if (std::filesystem::exists(flower))
    run_case("octaflower 512 (aa)", mesh_of(volume::load(flower), 127.5f), runs);
  std::printf(
      "Griffin et al. Table 1 (GTX480): engine lines 27.0 ms vs "
      "curvature 26.7 ms (+1%%)\n");
  return 0;
}
