#pragma once
// A label map's labels, each as its own surface: the label's indicator volume (label_indicator),
// the marching-cubes surface at its half level, and optionally that surface's curvature estimated
// on the indicator alone (never across a label boundary). for_each_label_surface visits them one
// label at a time; label_surfaces merges them into one mesh with the Label arrays
// (label_merge.h), as the command line's --labels and the Python module's extract_labels and
// curvature_labels make it (docs/labels.md).
//
// The library does not choose a device or an estimator: the caller passes the extraction and the
// curvature as callables (the command line's extract_surface and estimate_curvature with its
// options; the Python module's with its arguments), so every caller gets the same surfaces for the
// same calls. Errors and warnings are the caller's to word: the labels whose surface is empty are
// returned, not reported.
//
// Threading: everything runs on the calling thread, one label after another, the callables and the
// visitor included (a caller that wants a device lock or a progress bar takes it in its callables).
// `map` is only read; calls on different maps, or on the same map from several threads, may run
// at once as far as this library goes (the callables decide the rest).
// Tested in tests/labels/test_label_surfaces.cpp.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "labels/label_map.h"
#include "labels/label_merge.h"
#include "volume/volume.h"

namespace isocurv::labels {

/// The isovalue of every label's surface: half way between the indicator's 0 and 1.
inline constexpr float kIndicatorIsovalue = 0.5f;

/// The indicator margin (indicator_margin, in voxels) a label map `map` needs for the volume
/// estimator at the binary scale (curvature::kBinaryScaleVoxels) or at the largest of `scales`
/// (Gaussian sigmas in world units, as --scale gives them; 0 stands for 'auto', which is the
/// binary scale on an indicator), converted to voxels of map's smallest spacing. Enough for the
/// mesh estimators too (they read no volume). The command line's and the Python module's margin.
int scale_margin(const volume::Volume& map, const std::vector<double>& scales = {});

/// One label's surface, as for_each_label_surface hands it to its visitor.
struct LabelSurface {
  Label label;               ///< its value, voxel count and box (in map's index space)
  /// Its indicator (label_indicator with LabelSurfaceSteps::margin): 1 on the label's voxels, 0
  /// elsewhere, on the label's box grown by the margin, in map's index space and transform.
  volume::Volume indicator;
  float isovalue = kIndicatorIsovalue;  ///< the surface's level in `indicator`
  /// LabelSurfaceSteps::extract's surface of `indicator` at `isovalue`, in world coordinates
  /// (map's units); never empty (labels without a surface are not visited).
  Mesh mesh;
  /// LabelSurfaceSteps::curvature's field for `mesh` (one entry per vertex), or empty without it.
  std::optional<curvature::CurvatureField> field;
};

/// How for_each_label_surface makes each label's surface.
struct LabelSurfaceSteps {
  /// The indicators' margin in voxels (label_indicator; at least 1): scale_margin for the
  /// volume estimator's scale. It sets the indicator's domain, and so the mesh's vertex order.
  int margin = 2;
  /// The isosurface of an indicator at `isovalue` (required): e.g. mc::extract on a device, or
  /// mc::extract_reference.
  std::function<Mesh(const volume::Volume& indicator, float isovalue)> extract;
  /// The curvature of a label's (non-empty) `mesh`, estimated on its `indicator` at `isovalue`
  /// (e.g. curvature::estimate_field with the volume estimator); empty: no curvature.
  std::function<curvature::CurvatureField(const Mesh& mesh, const volume::Volume& indicator,
                                          float isovalue)>
      curvature;
  /// Called, when set, as each stage begins: "labels" (cutting a label out, merging it),
  /// "extract", and "" when a stage ends, for a caller's timings (the curvature callable times
  /// itself). for_each_label_surface never calls it while its visitor runs; label_surfaces calls
  /// it around each merge ("labels", then "").
  std::function<void(const std::string& stage)> stage;
};

/// Visits the labels of label map `map` named in `picked` (from label_map_labels / pick_labels of
/// `map`), in `picked`'s order: for each, its indicator (label_indicator at steps.margin), the
/// indicator's surface at kIndicatorIsovalue (steps.extract), its curvature when steps.curvature
/// is set, then visit(surface). A label whose surface is empty (it fills the whole of map's
/// domain) is not visited, and gets no curvature: its value is returned, in
/// `picked`'s order, for the caller to warn about.
/// Lifetime: `surface` lives only during its visit (the next label reuses nothing of it); the
/// visitor may move its indicator, mesh or field out to keep them. At most one label's indicator,
/// mesh and field are held at a time by this function.
/// @throw Error from label_indicator (a margin below 1), and whatever the callables or the visitor
///        throw (passed on as thrown; the remaining labels are not visited).
std::vector<std::int64_t> for_each_label_surface(
    const volume::Volume& map, const std::vector<Label>& picked, const LabelSurfaceSteps& steps,
    const std::function<void(LabelSurface& surface)>& visit);

/// The labels' surfaces merged, and the labels left out.
struct LabelSurfaces {
  /// The visited labels' surfaces one after another (append_label), in `picked`'s order: their
  /// mesh, their fields (with steps.curvature; else only the per-vertex "Label"), the per-triangle
  /// labels and where each label lies (parts). Empty when no label had a surface.
  LabelledMesh merged;
  std::vector<std::int64_t> empty;  ///< the labels without a surface, left out
};

/// for_each_label_surface, each surface appended to one LabelledMesh (labels never share a vertex,
/// so each label's surface keeps its own, closed, components): the --labels mesh.
/// @throw as for_each_label_surface, and append_label's Error past 2^32 - 1 vertices.
LabelSurfaces label_surfaces(const volume::Volume& map, const std::vector<Label>& picked,
                             const LabelSurfaceSteps& steps);

}  // namespace isocurv::labels
