// Mesh-file write benchmark: a mesh with every curvature array written as .vtp with each
// compressor (zlib at VTK's default level 5 is what isocurv wrote before --compress existed), and
// as .ply for comparison; medians from the same run, with file sizes. Not a test: prints a table.
//
//   bench_write [--volume PATH] [--iso V] [--runs N]     (default: the lobster CT at its Otsu
//   value)
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "core/cl_device.h"
#include "curvature/ao_scale.h"
#include "curvature/estimate.h"
#include "io/compression.h"
#include "io/mesh_file.h"
#include "mc/extract.h"
#include "volume/load.h"

using namespace isocurv;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  bench::keep_freed_memory();
  std::string path = std::string(ISOCURV_SHARED_DATASETS) + "/lobster/lobster.vol";
  float iso = -1;
  bool iso_given = false;
  int runs = 7;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--volume") && i + 1 < argc)
      path = argv[++i];
    else if (!std::strcmp(argv[i], "--iso") && i + 1 < argc)
      iso = std::strtof(argv[++i], nullptr), iso_given = true;
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
      runs = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_write [--volume PATH] [--iso V] [--runs N]\n");
      return 2;
    }
  }
  const volume::Volume v = volume::load(path);
  if (!iso_given) iso = float(v.stats.suggested_isovalue);
  Device& dev = Device::default_device();
  const Mesh mesh = mc::extract(v, iso, dev);
  curvature::Options co;
  co.ao_scale = curvature::default_ao_scale(mesh);
  const curvature::CurvatureField field = curvature::estimate(mesh, dev, co);
  std::printf("%s at %g: %zu vertices, %zu triangles, every curvature array; medians of %d\n",
              path.c_str(), iso, mesh.positions.size(), mesh.triangles.size(), runs);

  const fs::path dir =
      fs::temp_directory_path() / ("isocurv_bench_write_" + std::to_string(getpid()));
  fs::create_directories(dir);
  struct Case {
    std::string label, file;
    io::Compression c;
  };
  std::vector<Case> cases = {{"vtp zlib:5 (before)", "a.vtp", {io::Compressor::zlib, 5}},
                             {"vtp zlib:1", "b.vtp", {io::Compressor::zlib, 1}},
                             {"vtp zlib:3", "c.vtp", {io::Compressor::zlib, 3}},
                             {"vtp lz4:1", "d.vtp", {io::Compressor::lz4, 1}},
                             {"vtp lz4:5", "e.vtp", {io::Compressor::lz4, 5}},
                             {"vtp lz4:9", "f.vtp", {io::Compressor::lz4, 9}},
                             {"vtp none", "g.vtp", {io::Compressor::none, 0}},
                             {"ply", "h.ply", {}}};
  std::vector<bench::Timed> methods;
  for (const Case& k : cases) {
    const std::string out = (dir / k.file).string();
    methods.push_back(
        {[&mesh, &field, out, c = k.c] { io::write_mesh(out, mesh, &field, c); }, runs});
  }
  const std::vector<double> t = bench::medians_ms(methods);
  std::printf("%-22s %9s %10s %12s\n", "format", "ms", "MB", "before / it");
  for (std::size_t i = 0; i < cases.size(); ++i)
    std::printf("%-22s %9.1f %10.2f %12.2f\n", cases[i].label.c_str(), t[i],
                double(fs::file_size(dir / cases[i].file)) / 1e6, t[0] / t[i]);
  fs::remove_all(dir);
  return 0;
}
