#pragma once
// Time series: `--time-series` makes run, curvature, extract, features and lines treat their
// inputs as the frames of one series (a file series, the grids of a multi-grid .vdb, or a flipbook
// of mesh files) and write one output per frame, a ParaView collection DIR/series.pvd
// (io/pvd_collection.h) and DIR/series.json. Frames are streamed: one is loaded, computed, written
// and dropped before the next is read, so memory does not grow with the number of frames.
#include <functional>
#include <string>
#include <vector>

#include "app/pipeline.h"

namespace isocurv::app {

/// The command-line state of --time-series.
struct SeriesCli {
  bool enabled = false;    ///< --time-series
  double time_step = 1.0;  ///< --time-step: frame i has time i * time_step
};

/// Adds --time-series and --time-step to `cmd`.
void add_series_options(CLI::App& cmd, SeriesCli& s);

/// One frame of a series.
struct SeriesFrame {
  std::string path;  ///< the file to read
  std::string
      grid;  ///< a multi-grid .vdb: the grid of this frame (else empty: --grid or the default)
  std::string label;  ///< unique name of the frame's outputs (file stem, or <stem>_<grid>)
  double time = 0;    ///< index * time_step
};

/// The frames of `inputs` (paths or globs): every match of every glob and every given path,
/// together in natural order (core/natural_order.h: frame_2 before frame_10, whatever order the
/// shell or the command line gave), a path given twice kept once; a .vdb with several float grids
/// (and no `grid` option) gives one frame per grid in natural order of the grid names. Labels are
/// the file stems (name up to its first dot), <stem>_<grid> for grids, made unique with _2, _3.
/// @throw Error for a glob matching nothing, or no frame at all.
std::vector<SeriesFrame> series_frames(const std::vector<std::string>& inputs,
                                       const std::string& grid, double time_step);

/// Computes and writes one frame: `o` is the command's options with the frame's grid set (and,
/// after the first frame of a volume series, its isovalue: every frame is cut at the same value);
/// `out` the output path (DIR/<label>.vtp, or the folder DIR/<label>/ for run). Returns the
/// frame's report (surface_report and the command's own fields; "mesh" names the file the .pvd
/// lists when it is not `out`; "isovalue" when a volume).
using FrameFunction = std::function<nlohmann::json(const SeriesFrame& frame, CommonOptions& o,
                                                   const std::string& out)>;

/// How a command lays out a series.
struct SeriesLayout {
  std::string command;            ///< "run", "curvature", ... (for series.json)
  std::string dir;                ///< -o: the output folder (created if missing)
  bool folder_per_frame = false;  ///< run: each frame writes the folder DIR/<label>/
  std::string extension = "vtp";  ///< of the per-frame file the .pvd lists
};

/// Runs `frame_fn` over the frames of `inputs` in order. After each frame DIR/series.pvd lists the
/// frames written so far (rewritten atomically), and DIR/series.json (also rewritten after every
/// frame) gives per frame its time, input, output, counts, curvature statistics, timings_ms and
/// the process's peak resident memory so far (`peak_rss_kb`, VmHWM), and the totals. The first
/// bad frame stops the series: the frames already written and the .pvd listing them stay, the
/// JSON records the failure, and an Error "frame K of N (<input>): <problem>" is thrown.
/// Prints one summary line (or the JSON with --json) at the end.
void run_series(const std::vector<std::string>& inputs, const SeriesCli& cli,
                const SeriesLayout& layout, CommonOptions o, const FrameFunction& frame_fn);

/// The process's peak resident set size in KiB (VmHWM of /proc/self/status; -1 if unknown).
long peak_rss_kb();

}  // namespace isocurv::app
