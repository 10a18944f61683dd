#pragma once
// curvature::estimate: per-vertex curvature of a triangle mesh on an OpenCL device.
// Tested in tests/curvature/closed_form_test.cpp, tests/curvature/degenerate_test.cpp.
#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "curvature/options.h"

namespace isocurv::curvature {

/// Wall-clock time of each step of one estimate() call, in milliseconds. The device steps are only
/// separated (the queue drained after each) when timings are requested.
struct Timings {
  double adjacency = 0;      ///< host: input checks and the vertex -> corner adjacency
  double upload = 0;         ///< host -> device copies (positions, triangles, adjacency, normals)
  double normals_areas = 0;  ///< vertex normals, mixed areas (one pair of passes, as Griffin) and
                             ///< the boundary flags
  double tensor = 0;         ///< per-face second fundamental form, rotated and weighted
  double directions = 0;     ///< per-vertex averaging and diagonalisation, H, K, shape, AO
  double derivative = 0;     ///< per-face curvature derivative and its per-vertex average
  double download = 0;       ///< device -> host copies into the CurvatureField
  double total = 0;          ///< the whole call
};

/// Per-vertex curvature of `mesh` computed on `device`: the same algorithm as estimate_reference
/// (see reference.h for the steps, conventions and degenerate cases) in float. Deterministic:
/// the same input on the same device gives bit-identical output. The program is built once per
/// device and device buffers are kept and reused between calls (calls are serialised per device).
/// An empty mesh gives an empty field. Throws isocurv::Error for invalid input (see check_input)
/// or an OpenCL failure. `timings`, when given, receives the step times.
CurvatureField estimate(const Mesh& mesh, Device& device, const Options& options = {},
                        Timings* timings = nullptr);

/// The same, into `out`, whose arrays keep their storage when large enough: repeated calls (the
/// explorer's slider) then touch no fresh memory. On a CPU device, first-touching newly allocated
/// arrays (~85 bytes per vertex) is a large share of a call's time.
void estimate(const Mesh& mesh, Device& device, const Options& options, CurvatureField& out,
              Timings* timings = nullptr);

}  // namespace isocurv::curvature
