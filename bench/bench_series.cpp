// Time-series benchmark: the update `isocurv view --time-series` runs when the frame changes
// (a new volume: mc::Mesher over it, extract at the current isovalue, curvature::estimate), over a
// 64-frame 128^3 gyroid_phase series (datasets/animated.h), beside the isovalue-slider update on
// one frame (the Mesher reused, as bench_explorer measures it). The target is 10 frames per
// second on 2 cores, extract + curvature without the render. Each frame's volume is sampled
// before its update and not timed (a series player reads the next frame ahead); loading a frame
// from a .vdb file is timed on its own. Peak resident memory (VmHWM, reset first) after 1 frame
// and after 100 frames shows that a streamed series does not grow. Not a test: prints a table.
//
//   bench_series [--frames N] [--res N] [--passes N]
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "datasets/animated.h"
#include "datasets/sample.h"
#include "datasets/write_vdb.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

volume::Volume frame_volume(int i, int frames, int res) {
  const auto field = datasets::make_animated_field("gyroid_phase", double(i) / frames);
  return datasets::sample(*field, res);
}

/// The explorer's update for a new frame: a Mesher over the new volume, extract, curvature.
std::size_t frame_update(const volume::Volume& v, float iso, Device& dev) {
  mc::Mesher mesher(v, dev);
  const Mesh mesh = mesher.extract(iso);
  curvature::Options co;
  co.ao_scale = curvature::default_ao_scale(mesh);
  const curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
  (void)field;
  return mesh.vertex_count();
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 64, res = 128, passes = 1;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--frames") && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--res") && i + 1 < argc)
      res = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--passes") && i + 1 < argc)
      passes = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_series [--frames N] [--res N] [--passes N]\n");
      return 2;
    }
  }
  Device& dev = Device::default_device();
  const float iso = 0.f;
  std::printf("bench_series: gyroid_phase, %d frames of %d^3, isovalue %g, device %s\n", frames,
              res, iso, dev.info().name.c_str());

  // Warm-up (program builds) on frame 0.
  const volume::Volume first = frame_volume(0, frames, res);
  frame_update(first, iso, dev);

  // The frame update over the series.
  std::vector<double> frame_ms;
  std::size_t vmin = SIZE_MAX, vmax = 0;
  for (int p = 0; p < passes; ++p)
    for (int i = 0; i < frames; ++i) {
      const volume::Volume v = frame_volume(i, frames, res);
      const auto t0 = Clock::now();
      const std::size_t n = frame_update(v, iso, dev);
      frame_ms.push_back(ms_since(t0));
      vmin = std::min(vmin, n);
      vmax = std::max(vmax, n);
    }
  // The isovalue slider on frame 0: the Mesher kept, 20 isovalues across (-1.2, 1.2).
  std::vector<double> slider_ms;
  {
    mc::Mesher mesher(first, dev);
    for (int p = 0; p < std::max(passes, 2); ++p)
      for (int k = 0; k < 20; ++k) {
        const float value = -1.2f + 2.4f * k / 19.f;
        const auto t0 = Clock::now();
        const Mesh mesh = mesher.extract(value);
        curvature::Options co;
        co.ao_scale = curvature::default_ao_scale(mesh);
        curvature::estimate(mesh, dev, co);
        slider_ms.push_back(ms_since(t0));
      }
  }
  // Loading a frame from a .vdb file (4 frames written to a temporary folder).
  std::vector<double> load_ms;
  {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("bench_series_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    for (int i = 0; i < 4; ++i) {
      const auto field = datasets::make_animated_field("gyroid_phase", double(i) / frames);
      const std::string path = (dir / ("g_" + std::to_string(i) + ".vdb")).string();
      datasets::write_vdb(*field, datasets::sample(*field, res), path);
      const auto t0 = Clock::now();
      volume::load(path);
      load_ms.push_back(ms_since(t0));
    }
    std::filesystem::remove_all(dir);
  }
  const double f_med = median(frame_ms), s_med = median(slider_ms), l_med = median(load_ms);
  const double f_max = *std::max_element(frame_ms.begin(), frame_ms.end());
  std::printf("%-36s %9s %9s %8s  %s\n", "update", "med ms", "max ms", "per s", "");
  std::printf("%-36s %9.1f %9.1f %8.1f  %s (target >= 10/s; %zu..%zu vertices)\n",
              "frame change (Mesher+extract+curv)", f_med, f_max, 1000 / f_med,
              1000 / f_med >= 10 ? "met" : "MISSED", vmin, vmax);
  std::printf("%-36s %9.1f %9.1f %8.1f\n", "isovalue slider (extract+curv)", s_med,
              *std::max_element(slider_ms.begin(), slider_ms.end()), 1000 / s_med);
  std::printf("%-36s %9.1f %9.1f %8.1f  (read ahead on another thread in a player)\n",
              "load a frame (.vdb)", l_med, *std::max_element(load_ms.begin(), load_ms.end()),
              1000 / l_med);
  std::printf("%-36s %9.1f %9s %8.1f\n", "frame change + load, in sequence", f_med + l_med, "",
              1000 / (f_med + l_med));

  // Peak memory of a streamed series: 1 frame, then 100 frames (frame i of the series mod N).
  malloc_trim(0);
  { std::ofstream("/proc/self/clear_refs") << "5"; }
  double after_one = 0;
  for (int i = 0; i < 100; ++i) {
    const volume::Volume v = frame_volume(i % frames, frames, res);
    frame_update(v, iso, dev);
    if (i == 0) after_one = bench::status_kb("VmHWM:") / 1024.0;
  }
  const double after_100 = bench::status_kb("VmHWM:") / 1024.0;
  std::printf(
      "peak RSS (VmHWM): after 1 frame %.1f MiB, after 100 frames %.1f MiB (x%.3f; limit "
      "x1.2)\n",
      after_one, after_100, after_100 / after_one);
  return 0;
}
