// isocurv_make_datasets OUTDIR [--res N] [--only NAME[,NAME...]] [--animated FRAMES] [--quiet]
// Samples every catalogue field (or the named ones) at N voxels along the longest box side
// (default 64) and writes OUTDIR/<name>.vdb. With --animated, the animated fields instead
// (datasets/animated.h), FRAMES frames at t = i / FRAMES each: OUTDIR/<name>/<name>_<i>.vdb
// (i not zero-padded: the series is read in natural order), and OUTDIR/pulsing_sphere_grids.vdb
// holding the pulsing sphere's frames as grids frame_0 ... frame_<FRAMES-1>. Runs at build time
// into <build>/datasets/.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "datasets/animated.h"
#include "datasets/field.h"
#include "datasets/sample.h"
#include "datasets/write_vdb.h"

namespace {

void usage(std::FILE* to) {
  std::fprintf(to,
               "usage: isocurv_make_datasets OUTDIR [--res N] [--only NAME[,NAME...]] [--animated FRAMES] [--quiet]\n"
               "Writes OUTDIR/<name>.vdb for each analytic field (N voxels along the longest side, default 64);\n"
               "--animated: OUTDIR/<name>/<name>_<i>.vdb, i < FRAMES, for each animated field instead.\n"
               "--quiet: no line per file written (the build runs it so).\n"
               "Fields:");
  for (const auto& n : isocurv::datasets::field_names()) std::fprintf(to, " %s", n.c_str());
  std::fprintf(to, "\nAnimated fields:");
  for (const auto& n : isocurv::datasets::animated_field_names()) std::fprintf(to, " %s", n.c_str());
  std::fprintf(to, "\n");
}

}  // namespace

int main(int argc, char** argv) {
  namespace ds = isocurv::datasets;
  std::string outdir;
  int res = 64, frames = 0;
  bool only_given = false, quiet = false;
  std::vector<std::string> names = ds::field_names();
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        usage(stdout);
        return 0;
      } else if (a == "--quiet") {
        quiet = true;
      } else if (a == "--res" && i + 1 < argc) {
        res = std::stoi(argv[++i]);
      } else if (a == "--only" && i + 1 < argc) {
        names.clear();
        only_given = true;
        std::stringstream list(argv[++i]);
        for (std::string n; std::getline(list, n, ',');) names.push_back(n);
      } else if (a == "--animated" && i + 1 < argc) {
        frames = std::stoi(argv[++i]);
        if (frames < 1) throw std::runtime_error("--animated needs at least 1 frame");
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
    if (frames > 0) {
      if (!only_given) names = ds::animated_field_names();
      for (const auto& name : names) {
        const auto start = std::chrono::steady_clock::now();
        const std::filesystem::path dir = std::filesystem::path(outdir) / name;
        std::filesystem::create_directories(dir);
        std::vector<std::unique_ptr<ds::Field>> fields;
        std::vector<isocurv::volume::Volume> volumes;
        for (int f = 0; f < frames; ++f) {
          const double t = double(f) / frames;
          auto field = ds::make_animated_field(name, t);
          auto volume = ds::sample(*field, res);
          ds::write_vdb(*field, volume, (dir / (name + "_" + std::to_string(f) + ".vdb")).string());
          if (name == "pulsing_sphere") {  // kept for the multi-grid file
            fields.push_back(std::move(field));
            volumes.push_back(std::move(volume));
          }
        }
        if (!volumes.empty()) {
          std::vector<ds::NamedGrid> grids;
          for (int f = 0; f < frames; ++f)
            grids.push_back({fields[f].get(), &volumes[f], "frame_" + std::to_string(f), double(f) / frames});
          ds::write_vdb_grids(grids, (std::filesystem::path(outdir) / (name + "_grids.vdb")).string());
        }
        const double secs =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!quiet)
          std::printf("%s: %d frames of %d^3 (longest side), %.2f s\n", dir.string().c_str(), frames,
                    res, secs);
      }
      return 0;
    }
    for (const auto& name : names) {
      const auto start = std::chrono::steady_clock::now();
      const auto field = ds::make_field(name);
      const auto volume = ds::sample(*field, res);
      const std::string path = (std::filesystem::path(outdir) / (name + ".vdb")).string();
      ds::write_vdb(*field, volume, path);
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const auto dim = volume.domain.dim();
      if (!quiet)
        std::printf("%s: %dx%dx%d, %.1f KiB, %.2f s\n", path.c_str(), dim.x(), dim.y(), dim.z(),
                  std::filesystem::file_size(path) / 1024.0, secs);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isocurv_make_datasets: %s\n", e.what());
    return 1;
  }
  return 0;
}
