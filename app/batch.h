#pragma once
// Several inputs, several isovalues, one process: `isocurv run|extract|curvature|features|lines
// IN... -o DIR` and `--iso V1,V2,...`. Each input writes under DIR/<input stem>/, DIR/summary.json
// lists every (input, isovalue) entry; a bad input is reported and the others still run.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/pipeline.h"
#include "app/render_options_cli.h"
#include "viz/render.h"

namespace isocurv::app {

/// The command a batch runs per entry: one of run_batch's own, or `step`, a command's own work
/// (BatchStep: features, lines).
enum class BatchKind { extract, curvature, run, step };

/// A command's own work per batch entry, run inside run_batch's loop (its inputs, folders,
/// loading ahead, writer thread, failures and summary.json): `compute` on the main thread (the
/// device's), then `write` of what it returned, on the writer thread with --jobs 2.
struct BatchStep {
  /// What one computed entry leaves for the writer.
  struct Output {
    /// Writes the entry's output file at `path` (a temporary name with the output's extension,
    /// renamed into place with stats.json). May run on another thread; the Surface given to
    /// `compute` stays alive (and untouched) until it has run.
    std::function<void(const std::string& path)> write;
    /// The command's --json report for this input (surface_report and its counts): completed with
    /// "input", "output" and "timings_ms" and written as the entry's stats.json.
    nlohmann::json report = nlohmann::json::object();
    /// The keys of `report` copied into the entry in summary.json (the counts).
    std::vector<std::string> summary_keys;
  };
  std::string command;  ///< "features", "lines": summary.json's "command"
  bool mesh_input = true;  ///< mesh files (.vtp .ply .obj .stl) are inputs too, not only volumes
  /// Computes one entry, stages timed in `timer`: `s` is the volume's isosurface at the entry's
  /// isovalue (s.volume and s.isovalue set, the empty surface refused), or the mesh file as read
  /// (load_surface; not yet prepare_mesh_for_curvature'd). @throw for a failing entry.
  std::function<Output(Surface& s, const std::string& input, StageTimer& timer)> compute;
};

/// Everything a batch needs besides the CommonOptions.
struct BatchRequest {
  BatchKind kind = BatchKind::extract;
  const BatchStep* step = nullptr;  ///< BatchKind::step: the command's work
  std::vector<std::string> inputs;  ///< paths or globs (a glob is expanded, sorted)
  std::vector<float> isovalues;     ///< empty: each volume's suggested isovalue
  std::string dir;                  ///< the output folder (-o)
  std::string format = "vtp";       ///< mesh (step: output) extension without the dot
  int jobs = 1;  ///< >= 2: the next input is loaded, and the last one's mesh written, while the
                 ///< current one is computed (two extra threads; the device stays on this one)
  const RenderCli* render = nullptr;  ///< run: the PNG's options (render_options_for per input)
};

/// The command-line state of a command that can run as a batch.
struct BatchCli {
  std::vector<std::string> inputs;                ///< the positional inputs
  std::string iso;                                ///< --iso text: V or V1,V2,...
  std::string format = "vtp";                     ///< --format (batch mesh format)
  int jobs = 1;                                   ///< --jobs
  bool format_given = false, jobs_given = false;  ///< given on the command line
};

/// Adds the positional INPUT... (named `input_name`), --iso V[,V2,...] and --jobs, and --format
/// choosing from `formats` when `formats` is not empty (run has its own --format).
void add_batch_options(CLI::App& cmd, BatchCli& b, const std::string& input_name,
                       const std::string& input_help, const std::vector<std::string>& formats);

/// Called first in the command's callback: parses --iso; for one input at one isovalue sets o.iso
/// and returns false (the command goes on as for a single file; --format and --jobs, which apply
/// to batches only, are then an Error); otherwise runs the batch with -o `dir` as the folder and
/// returns true. `format` overrides b.format when not empty.
bool run_as_batch(const BatchCli& b, CommonOptions& o, BatchKind kind, const std::string& dir,
                  const RenderCli* render = nullptr, const std::string& format = "");

/// The same for a command with its own BatchStep (features, lines): true when it ran as a batch
/// (BatchKind::step, b.format the output extension); false for one input at one isovalue (o.iso
/// set; --format and --jobs an Error). `before` (when given) runs first when it is a batch, before
/// the output folder is made: the checks of options that every entry would fail on.
bool run_as_batch(const BatchCli& b, CommonOptions& o, const BatchStep& step,
                  const std::string& dir, const std::function<void()>& before = {});

/// For --time-series (app/series.h), called first: --iso must be one value (it sets o.iso; every
/// frame is cut there), and --format and --jobs, which are for batches, are an Error.
void require_series_cli(const BatchCli& b, CommonOptions& o);

/// Parses --iso "V1,V2,..." (finite numbers, at least one, no repeats). @throw Error naming the
/// bad item.
std::vector<float> parse_isovalues(const std::string& text);

/// True when the command must run as a batch: several inputs (after expanding globs), a glob, or
/// several isovalues. One input at one isovalue keeps the single-output layout (-o names the file
/// or, for run, the folder).
bool is_batch(const std::vector<std::string>& inputs, const std::vector<float>& isovalues);

/// Refuses an output folder (`-o` of a batch, sweep, series, run or deform) that does not exist
/// yet and is named like a file (.vtp .vtk .ply .obj .stl .png .json .svg .pvd .csv .vti .nrrd
/// ...): one would otherwise get a folder called `sw.vtp`. `what` names the output in the
/// message ("several inputs or isovalues", "a time series", ...). @throw Error naming it.
void require_folder_name(const std::string& dir, const std::string& what);

/// The output folder `dir` made ready: require_folder_name, then an existing file refused and the
/// folder created (with its parents) if missing. @throw Error naming `dir`.
void make_output_folder(const std::string& dir, const std::string& what);

/// The output name's suffix for isovalue `iso` in a sweep: "_iso40", "_iso0.5", "_iso-1e-05".
std::string iso_suffix(float iso);

/// The file name without its extension, naming outputs: "Al.100.vol" -> "Al.100", and a
/// compression suffix goes with the extension ("head.nii.gz" -> "head"); `fallback` when that is
/// empty.
std::string file_stem(const std::string& path, const std::string& fallback);

/// Runs the batch. Before any work, DIR is created (if missing) and must be writable (else an
/// Error). Each input gets DIR/<stem>/ (a stem met twice gets _2, _3, ...): the mesh (a step's
/// output) <stem>[_iso<V>].<format>, for run the PNG, and stats[_iso<V>].json; DIR/summary.json holds one
/// entry per input and isovalue with its status, outputs, counts and timings. A failing entry is
/// reported in one line on stderr (and in the summary) and the others still run; at the end an
/// Error saying how many failed is thrown if any did (exit status 1). With several isovalues a
/// volume is loaded once and its blocks indexed once (mc::Mesher).
void run_batch(const BatchRequest& request, const CommonOptions& o);

}  // namespace isocurv::app
