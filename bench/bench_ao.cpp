// AO benchmark: each curvature AO (ao/ao.h) against the ray-cast reference from the volume, per
// dataset: RMS difference and Pearson correlation per vertex, and the time of each method, all in
// one run. The pipeline is the command line's default: OpenCL marching cubes at the suggested
// isovalue, volume-gradient normals, Rusinkiewicz curvature, AO radius 4 mean edge lengths.
//   bench_ao [--quick] [--datasets DIR]   (DIR: the bundled build/datasets; --quick: torus and
//                                          the lobster only)
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "ao/ao.h"
#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "mc/extract.h"
#include "volume/gradient_normals.h"
#include "volume/load.h"

using namespace isocurv;

namespace {

struct Agreement {
  double rms = 0, r = 0, mean = 0;
};

/// RMS difference and Pearson r of a against b over the vertices not on an open boundary.
Agreement agreement(const std::vector<float>& a, const std::vector<float>& b,
                    const std::vector<std::uint8_t>& boundary) {
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, se = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!boundary.empty() && boundary[i]) continue;
    const double x = a[i], y = b[i];
    n += 1, sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y, se += (x - y) * (x - y);
  }
  Agreement g;
  if (n == 0) return g;
  g.rms = std::sqrt(se / n);
  g.mean = sa / n;
  const double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
  g.r = va > 0 && vb > 0 ? (sab / n - sa * sb / (n * n)) / std::sqrt(va * vb) : 0;
  return g;
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void run_case(const std::string& name, const volume::Volume& v) {
  Device& dev = Device::default_device();
  const float iso = float(v.stats.suggested_isovalue);
  const Mesh mesh = mc::extract(v, iso, dev);
  if (mesh.triangles.empty()) {
    std::printf("%-16s no surface at iso %g\n", name.c_str(), iso);
    return;
  }
  const volume::MeshNormals normals = volume::gradient_normals_for_mesh(v, mesh);
  curvature::Options co;
  co.vertex_normals = &normals.normals;
  co.ao_scale = curvature::default_ao_scale(mesh);
  const curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
  const double curv_ms = bench::medians_ms({{[&] { curvature::estimate(mesh, dev, co); }, 3}})[0];

  auto run = [&](ao::Method m, int runs, double* ms) {
    curvature::CurvatureField f = field;
    ao::Options o;
    o.method = m;
    o.radius = co.ao_scale;
    ao::compute(mesh, f, {&v, iso}, o);
    if (runs > 1) {
      *ms = bench::medians_ms({{[&] {
                                  curvature::CurvatureField g = field;
                                  ao::compute(mesh, g, {&v, iso}, o);
                                },
                                runs}})[0];
    }
    return f.ao;
  };
  double ray_ms = 0, cos_ms = 0;
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<float> ray = run(ao::Method::raycast, 1, nullptr);
  ray_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  const std::vector<float> ray_cos = run(ao::Method::raycast_cos, 1, nullptr);
  cos_ms = ms_since(t0);
  const Agreement self = agreement(ray, ray, field.boundary);
  std::printf(
      "%-16s %8zu  rho %.3g  curvature %.0f ms; raycast %.0f ms (mean %.3f), raycast-cos "
      "%.0f ms (mean %.3f)\n",
      name.c_str(), mesh.vertex_count(), co.ao_scale, curv_ms, ray_ms, self.mean, cos_ms,
      agreement(ray_cos, ray_cos, field.boundary).mean);
  for (ao::Method m :
       {ao::Method::griffin, ao::Method::griffin_exact, ao::Method::hattori, ao::Method::prantl}) {
    double ms = 0;
    const std::vector<float> a = run(m, 5, &ms);
    const Agreement g = agreement(a, ray, field.boundary),
                    gc = agreement(a, ray_cos, field.boundary);
    std::printf(
        "  %-14s mean %.3f  vs raycast: RMS %.3f r %.3f | vs raycast-cos: RMS %.3f r %.3f"
        "  %.2f ms\n",
        ao::method_name(m), g.mean, g.rms, g.r, gc.rms, gc.r, ms);
  }
  // Hattori's umbilic-mean variant
  {
    curvature::CurvatureField f = field;
    ao::Options o;
    o.method = ao::Method::hattori;
    o.hattori_half = true;
    o.radius = co.ao_scale;
    ao::compute(mesh, f, {&v, iso}, o);
    const Agreement g = agreement(f.ao, ray, field.boundary),
                    gc = agreement(f.ao, ray_cos, field.boundary);
    std::printf(
        "  %-14s mean %.3f  vs raycast: RMS %.3f r %.3f | vs raycast-cos: RMS %.3f r %.3f\n",
        "hattori-half", g.mean, g.rms, g.r, gc.rms, gc.r);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  bool quick = false;
  std::string dir = "datasets";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--quick"))
      quick = true;
    else if (!std::strcmp(argv[i], "--datasets") && i + 1 < argc)
      dir = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_ao [--quick] [--datasets DIR]\n");
      return 2;
    }
  }
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 2);
  openvdb::initialize();
  std::printf(
      "device: %s; 2 threads; rho = 4 mean edge lengths; 256 rays; formula times are "
      "medians of 5 (CPU, on top of the curvature); open-boundary vertices left out\n",
      Device::default_device().info().name.c_str());
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".vdb") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    if (quick && f.stem() != "torus") continue;
    run_case(f.stem().string(), volume::load(f.string()));
  }
  const std::string lobster = std::string(ISOCURV_SHARED_DATASETS) + "/lobster/lobster.vol";
  if (std::filesystem::exists(lobster)) {
    volume::LoadOptions lo;
    lo.spacing = std::array<double, 3>{1, 1, 1.4};
    run_case("lobster", volume::load(lobster, lo));
  }
  return 0;
}
