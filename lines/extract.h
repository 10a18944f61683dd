#pragma once
// lines::extract: the per-face feature-line extraction on an OpenCL device.
#include "core/cl_device.h"
#include "lines/segments.h"

namespace isocurv::lines {

/// Wall-clock time of one extract() call, in milliseconds (the queue is drained
/// between the steps only when timings are asked for).
struct Timings {
  double upload =
      0; ///< host -> device copies of the mesh and field (and the adjacency)
  double view = 0;  ///< per-vertex view quantities and their smoothing
  double count = 0; ///< the per-face count and its download
  double emit =
      0; ///< host scan of the counts, the emitting pass and the download
  double total = 0;
};

/// The same segments as extract_reference (lines/reference.h states the rules),
/// computed in float on `device`: three kernels (per-vertex view quantities;
/// per face, the number of segments; the faces that have some write theirs at
/// offsets from a host scan, in face order). Deterministic. Device buffers are
/// kept between calls (one call at a time per device). An empty mesh gives no
/// segments. `upload_mesh` false reuses the mesh and field uploaded by the
/// previous call on this device (the explorer moving only its camera); the
/// caller guarantees they are unchanged.
/// @throw Error for invalid input (check_input), bad thresholds or an OpenCL
/// failure.
Segments extract(const Mesh &mesh, const curvature::CurvatureField &field,
                 const Camera &camera, const Options &options, Device &device,
                 Timings *timings = nullptr, bool upload_mesh = true);

} // namespace isocurv::lines
