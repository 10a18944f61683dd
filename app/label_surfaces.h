#pragma once
// --labels, --label and --split: a label map's surfaces, one per label, for extract, curvature,
// run, render and measure (docs/labels.md).
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

#include "app/pipeline.h"
#include "core/atomic_file.h"
#include "labels/label_surfaces.h"

namespace isocurv::app {

/// Adds --labels and --label LIST, and --split when the command writes mesh files.
void add_label_options(CLI::App& cmd, CommonOptions& o, bool with_split);

/// The surfaces of the labels of the label map `path` (all of them, or --label's), as one
/// Surface (labels::label_surfaces with the command's extraction and curvature): `volume` the
/// label map, `mesh` the labels' surfaces one after another, each the
/// marching-cubes surface at 0.5 of its indicator (labels::label_indicator: touching labels each
/// get a closed surface), `label_cells` and `label_parts` saying which is which. With
/// `curvature`, each label's curvature is estimated on its own indicator (estimate_curvature:
/// the volume estimator by default, at the binary scale) and `field` holds them all; without it,
/// `field` holds only the per-vertex "Label". isovalue is 0.5. A --label value the map lacks,
/// or a label whose surface is empty, is named in a warning line (unless --quiet). `hooks` (with
/// `curvature`): what features --labels adds (LabelHooks).
/// @throw Error naming `path` for a mesh file, --iso (each label has its own level), a float
///        volume, more than labels::kMaxLabels labels, or when no picked label has a surface.
/// A label map as --labels and --label pick it: the map and the labels to make surfaces of.
struct PickedLabels {
  volume::Volume map;
  std::vector<labels::Label> picked;  ///< never empty
};

/// Loads the label map `path` (stages "load", "labels") and picks --label's labels (all without
/// it), warning (unless --quiet) about --label values the map lacks, and opens the device.
/// @throw Error naming `path` for a mesh file, --iso, a float volume, more than
///        labels::kMaxLabels labels, a map without labels, or none of --label's in it.
PickedLabels pick_labels(const std::string& path, const CommonOptions& o, StageTimer& timer);

/// After the labels of `path` were visited: a warning line (unless --quiet) naming the labels
/// `empty` whose surface was empty (labels::filling_labels_note), and an Error naming `path`
/// when no label had a surface (`any` false).
void report_label_visits(const std::string& path, const std::vector<std::int64_t>& empty,
                         bool any, const CommonOptions& o);

/// The options of each label's surface: the indicators' margin for o's scales and o's
/// extraction (extract_surface); no curvature, and `timer` takes the stages.
labels::LabelSurfaceSteps label_steps(const volume::Volume& map, const CommonOptions& o,
                                      StageTimer& timer);

/// What a command adds to load_label_surfaces, label by label on the calling thread:
/// - `margin`, called once with the label map before any label: the least indicator margin
///   (voxels) the command's own reach needs (features' radius), raising the scale's when larger;
/// - `field`, on each label's curvature before the labels are merged: `mesh` the label's surface,
///   `indicator` its indicator volume (isovalue labels::kIndicatorIsovalue), `field` its
///   curvature, to add extra arrays to (every label must add the same ones, or merging drops
///   them).
struct LabelHooks {
  std::function<int(const volume::Volume& map)> margin;
  std::function<void(const Mesh& mesh, const volume::Volume& indicator,
                     curvature::CurvatureField& field)>
      field;
};

Surface load_label_surfaces(const std::string& path, const CommonOptions& o, StageTimer& timer,
                            bool curvature, const LabelHooks& hooks = {});

/// Checks, before any work, that `out` can take a label map's surfaces: a writable file, or with
/// --split a folder name (not an existing file). @throw Error naming `out`.
void require_label_output(const std::string& out, const CommonOptions& o);

/// Writes a label map's surfaces `s` (from `in`) to `out`: one mesh file with the Label arrays
/// (and the field), or with --split the folder `out` with one .vtp per label; all written or none.
/// Returns what --json reports about it: "output" and "output_bytes", or "outputs" (a list).
nlohmann::json write_label_output(const Surface& s, const std::string& in, const std::string& out,
                                  const CommonOptions& o, StageTimer& timer);

/// extract and curvature with --labels: require_label_output, load_label_surfaces (with
/// `curvature` or not), write_label_output; returns the --json report (surface_report, the
/// outputs, compression, device, programs, timings_ms).
nlohmann::json label_surfaces_to_files(const std::string& in, const std::string& out,
                                       const CommonOptions& o, bool curvature);

/// The normal (non --json) summary of extract/curvature --labels: "wrote out.vtp (1.2 MB): 3
/// labels, 12345 vertices<what>, 24680 triangles", or the --split folder's file count.
void print_label_summary(const nlohmann::json& report, const std::string& what);

/// --split: one mesh file per label of `s`, `dir`/label_<value>.<format>, each with its arrays
/// (the field's slice, the Label arrays) and `context`, added to `outputs` (written together or
/// not at all by the caller's commit). Returns the paths in the labels' order.
std::vector<std::string> write_split_labels(const Surface& s, const std::string& dir,
                                            const std::string& format,
                                            const CommonOptions& o, const io::Metadata& context,
                                            AtomicFileSet& outputs);

}  // namespace isocurv::app
