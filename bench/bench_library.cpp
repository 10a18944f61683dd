// The C++ library's extract + volume normals + curvature on one volume, warm, median of N: the
// figure bench/python/bench_headless.py sets the Python module's same calls beside.
//
//   bench_library --volume PATH [--iso V] [--runs N]      prints "median_ms <ms>"
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "core/error.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "mc/extract.h"
#include "volume/gradient_normals.h"
#include "volume/load.h"

using namespace isocurv;

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  std::string path;
  float iso = 0;
  bool iso_given = false;
  int runs = 9;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--volume") && i + 1 < argc)
      path = argv[++i];
    else if (!std::strcmp(argv[i], "--iso") && i + 1 < argc)
      iso = std::strtof(argv[++i], nullptr), iso_given = true;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
      runs = std::atoi(argv[++i]);
    else
      path.clear(), i = argc;
  }
  if (path.empty()) {
    std::fprintf(stderr, "usage: bench_library --volume PATH [--iso V] [--runs N]\n");
    return 2;
  }
  try {
    const volume::Volume v = volume::load(path);
    if (!iso_given) iso = float(v.stats.suggested_isovalue);
    Device& dev = Device::default_device();
    // What isocurv.extract + isocurv.curvature(mesh, volume) do.
    auto once = [&] {
      const Mesh mesh = mc::extract(v, iso, dev);
      const volume::MeshNormals n = volume::gradient_normals_for_mesh(v, mesh);
      curvature::Options co;
      co.vertex_normals = &n.normals;
      co.ao_scale = curvature::default_ao_scale(mesh);
      curvature::estimate(mesh, dev, co);
    };
    const double ms = bench::medians_ms({{once, runs}})[0];
    std::printf("median_ms %.3f\n", ms);
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_library: %s\n", e.what());
    return 1;
  }
  return 0;
}
