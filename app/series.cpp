#include "app/series.h"
#include "dist/world.h"

#include "app/batch.h"

#include <glob.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/natural_order.h"
#include "io/pvd_collection.h"
#include "volume/vdb_grid_names.h"

namespace isocurv::app {
namespace {

namespace fs = std::filesystem;

bool has_glob_chars(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

bool is_vdb(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".vdb";
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

long peak_rss_kb() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

void add_series_options(CLI::App& cmd, SeriesCli& s) {
  cmd.add_flag("--time-series", s.enabled,
               "Treat the inputs as the frames of one series (in natural order: frame_2 before "
               "frame_10; a multi-grid .vdb gives a frame per grid): -o is a folder with an "
               "output per frame, series.pvd (ParaView opens it as a time series) and "
               "series.json")
      ->group("Time series");
  cmd.add_option("--time-step", s.time_step, "Time between frames in the .pvd (frame i at i * DT)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str()
      ->group("Time series");
}

std::vector<SeriesFrame> series_frames(const std::vector<std::string>& inputs,
                                       const std::string& grid, double time_step) {
  std::vector<std::string> paths;
  for (const std::string& g : inputs) {
    std::error_code ec;
    if (!has_glob_chars(g) || fs::exists(g, ec)) {
      paths.push_back(g);
      continue;
    }
    glob_t found{};
    const int rc = ::glob(g.c_str(), 0, nullptr, &found);
    if (rc == 0)
      for (std::size_t i = 0; i < found.gl_pathc; ++i) paths.push_back(found.gl_pathv[i]);
    globfree(&found);
    if (rc != 0) throw Error(g, "no file matches this pattern");
  }
  natural_sort(paths);
  paths.erase(std::unique(paths.begin(), paths.end()), paths.end());
  std::vector<SeriesFrame> frames;
  for (const std::string& p : paths) {
    std::vector<std::string> grids;
    std::error_code ec;
    if (grid.empty() && is_vdb(p) && fs::is_regular_file(p, ec)) {
      try {
        grids = volume::vdb_grid_names(p);
      } catch (const Error&) {
        grids.clear();  // a broken file is one frame, whose load then names the problem
      }
    }
    if (grids.size() <= 1) {
      frames.push_back({p, "", file_stem(p, "frame"), 0});
    } else {
      for (const std::string& g : grids) frames.push_back({p, g, file_stem(p, "frame") + "_" + g, 0});
    }
  }
  if (frames.empty()) throw Error("--time-series: no frames");
  std::map<std::string, int> seen;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SeriesFrame& f = frames[i];
    const int n = ++seen[f.label];
    if (n > 1) f.label += "_" + std::to_string(n);
    f.time = double(i) * time_step;
  }
  return frames;
}

void run_series(const std::vector<std::string>& inputs, const SeriesCli& cli,
                const SeriesLayout& layout, CommonOptions o, const FrameFunction& frame_fn) {
  if (dist::World::get().size() > 1)
    throw Error("a time series does not run under mpirun with several ranks; run it without mpirun");
  const auto t_start = std::chrono::steady_clock::now();
  require_folder_name(layout.dir, "a time series");
  const std::vector<SeriesFrame> frames = series_frames(inputs, o.volume.grid, cli.time_step);
  make_output_folder(layout.dir, "a time series");
  const std::string pvd_path = (fs::path(layout.dir) / "series.pvd").string();
  const std::string json_path = (fs::path(layout.dir) / "series.json").string();
  io::PvdCollection pvd(pvd_path);
  nlohmann::json entries = nlohmann::json::array();
  std::optional<float> iso = o.iso;  // the first volume frame's, when not given
  auto summary = [&](const std::string& status) {
    nlohmann::json s = {{"command", layout.command},
                        {"status", status},
                        {"frames", frames.size()},
                        {"written", pvd.frames().size()},
                        {"pvd", pvd_path},
                        {"time_step", cli.time_step},
                        {"entries", entries},
                        {"device", device_name(o)},
                        {"programs", program_report()},
                        {"peak_rss_kb", peak_rss_kb()},
                        {"wall_ms", std::round(ms_since(t_start) * 1000) / 1000}};
    if (iso) s["isovalue"] = *iso;
    return s;
  };
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const SeriesFrame& f = frames[k];
    CommonOptions fo = o;
    if (!f.grid.empty()) fo.volume.grid = f.grid;
    fo.iso = iso;
    const std::string out = (fs::path(layout.dir) /
                             (layout.folder_per_frame ? f.label : f.label + "." + layout.extension))
                                .string();
    nlohmann::json entry = {{"frame", k}, {"time", f.time}, {"input", f.path}};
    if (!f.grid.empty()) entry["grid"] = f.grid;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      nlohmann::json r = frame_fn(f, fo, out);
      const std::string listed = r.contains("mesh") ? r["mesh"].get<std::string>() : out;
      pvd.add(f.time, listed);
      if (!iso && r.contains("isovalue")) iso = r["isovalue"].get<float>();
      entry["status"] = "ok";
      entry["output"] = listed;
      for (const char* key : {"isovalue", "vertices", "triangles", "curvature", "features",
                              "polylines", "segments", "timings_ms"})
        if (r.contains(key)) entry[key] = r[key];
      entry["frame_ms"] = std::round(ms_since(t0) * 1000) / 1000;
      entry["peak_rss_kb"] = peak_rss_kb();
      entries.push_back(entry);
      write_text_file(json_path, summary("running").dump(2) + "\n");
    } catch (const std::exception& e) {
      std::string problem = one_line(e.what());
      if (problem.rfind(f.path + ": ", 0) == 0) problem = problem.substr(f.path.size() + 2);
      entry["status"] = "failed";
      entry["error"] = problem;
      entries.push_back(entry);
      try {
        write_text_file(json_path, summary("failed").dump(2) + "\n");
      } catch (const std::exception&) {
      }
      throw Error("frame " + std::to_string(k) + " of " + std::to_string(frames.size()) + " (" +
                  f.path + (f.grid.empty() ? "" : ", grid " + f.grid) + "): " + problem + " (" +
                  std::to_string(k) + " frames written, listed in " + pvd_path + ")");
    }
  }
  const nlohmann::json s = summary("ok");
  write_text_file(json_path, s.dump(2) + "\n");
  if (o.json) {
    std::cout << s.dump(2) << "\n";
  } else if (!o.quiet) {
    std::cout << frames.size() << " frames written under " << layout.dir << " ("
              << format_number(std::round(ms_since(t_start))) << " ms); ParaView: " << pvd_path
              << ", statistics: " << json_path << "\n";
  }
}

}  // namespace isocurv::app
