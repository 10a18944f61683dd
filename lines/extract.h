#pragma once
// lines::extract: the per-face feature-line extraction on an OpenCL device.
// Tested in tests/lines/test_bad_input.cpp, tests/lines/test_ct_like.cpp.
#include "core/cl_device.h"
#include "lines/segments.h"

namespace isocurv::lines {

/// Wall-clock time of one extract() call, in milliseconds (the queue is drained
/// between the steps only when timings are asked for).
struct Timings {
  double checks = 0;  ///< the input checks and the thresholds (a median over the vertices)
  double upload = 0;  ///< binding the mesh and field (copies on devices with memory of their own)
  double ring = 0;    ///< the smoothing's 1-ring rows (lines/detail), once per mesh, on the host
  double view = 0;    ///< per-vertex view quantities and their smoothing
  double count = 0;   ///< the per-face count and its download
  double emit = 0;    ///< host scan of the counts, the emitting pass and the download
  double total = 0;
};

/// The same segments as extract_reference (lines/reference.h states the rules), computed in float
/// on `device` (lines/lines_kernels.cl):
/// - per vertex, the view quantities (n.v, kr, num), `smoothing_steps` passes over kr and num on
///   the 1-ring (its rows built once per mesh), and a byte of flags for the per-face tests;
/// - per face, from the flags alone, how many line types may cross it (nearly always none);
/// - the faces with some, in face order, write their segments at offsets from a host scan.
/// Deterministic. On devices that work in host memory (PoCL) the kernels read the mesh and the
/// field in place; elsewhere they are copied. Device buffers are kept between calls (one call at
/// a time per device). An empty mesh gives no segments. `upload_mesh` false reuses what the
/// previous call on this device prepared for the same mesh (the copies, the 1-ring: the explorer
/// moving only its camera); the caller guarantees that the mesh and field are unchanged.
/// @throw Error for invalid input (check_input), bad thresholds or an OpenCL
/// failure.
Segments extract(const Mesh& mesh, const curvature::CurvatureField& field, const Camera& camera,
                 const Options& options, Device& device, Timings* timings = nullptr,
                 bool upload_mesh = true);

}  // namespace isocurv::lines
