// isocurv_make_datasets OUTDIR [--res N] [--only NAME[,NAME...]]
// Samples every catalogue field (or the named ones) at N voxels along the longest box side
// (default 64) and writes OUTDIR/<name>.vdb. Runs at build time into <build>/datasets/.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "datasets/field.h"
#include "datasets/sample.h"
#include "datasets/write_vdb.h"

namespace {

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: isocurv_make_datasets OUTDIR [--res N] [--only NAME[,NAME...]]\n"
               "Writes OUTDIR/<name>.vdb for each analytic field (N voxels along the longest side, default 64).\n"
               "Fields:");
  for (const auto& n : isocurv::datasets::field_names()) std::fprintf(to, " %s", n.c_str());
  std::fprintf(to, "\n");
}

}  // namespace

int main(int argc, char** argv) {
  namespace ds = isocurv::datasets;
  std::string outdir;
  int res = 64;
  std::vector<std::string> names = ds::field_names();
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        usage(stdout);
        return 0;
      } else if (a == "--res" && i + 1 < argc) {
        res = std::stoi(argv[++i]);
      } else if (a == "--only" && i + 1 < argc) {
        names.clear();
        std::stringstream list(argv[++i]);
        for (std::string n; std::getline(list, n, ',');) names.push_back(n);
      } else if (outdir.empty() && !a.empty() && a[0] != '-') {
        outdir = a;
      } else {
        std::fprintf(stderr, "isocurv_make_datasets: unexpected argument '%s'\n", a.c_str());
        usage(stderr);
        return 2;
      }
    }
    if (outdir.empty()) {
      usage(stderr);
      return 2;
    }
    std::filesystem::create_directories(outdir);
    for (const auto& name : names) {
      const auto start = std::chrono::steady_clock::now();
      const auto field = ds::make_field(name);
      const auto volume = ds::sample(*field, res);
      const std::string path = (std::filesystem::path(outdir) / (name + ".vdb")).string();
      ds::write_vdb(*field, volume, path);
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto dim = volume.domain.dim();
      std::printf("%s: %dx%dx%d, %.1f KiB, %.2f s\n", path.c_str(), dim.x(), dim.y(), dim.z(),
                  std::filesystem::file_size(path) / 1024.0, secs);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isocurv_make_datasets: %s\n", e.what());
    return 1;
  }
  return 0;
}
