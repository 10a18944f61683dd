#pragma once
// The paper's evaluation protocol (Prantl et al. 2017, section 4; SEEDS-SPEC 4.4 (c), P-EV4):
// a mesh fully in view, the camera pulled back in steps, and at each step the mean squared
// difference between screen-space curvature and the object-space per-vertex curvature
// interpolated in the triangle each pixel sees.
// Tested in tests/screen/test_pull_back.cpp.
#include <vector>

#include "core/camera.h"
#include "core/cl_device.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "screen/estimate.h"

namespace isocurv::screen {

struct PullBackOptions {
  int width = 1024, height = 768;  ///< image size (pixels)
  int steps = 10;                  ///< camera distances
  /// Step k (0-based) puts the camera at (1 + k * distance_step) times the distance at which the
  /// mesh just fills the picture (fit_camera_to_points, perspective, `view`).
  double distance_step = 0.5;
  ViewSpec view;
};

/// The differences of one estimator at one camera distance, over the pixels it estimated.
struct PullBackError {
  double mse_H = 0, mse_K = 0;  ///< mean squared difference (1/length^2, 1/length^4)
  /// The same divided by the mean square of the object-space values over those pixels, so that
  /// H and K (whose units differ) can be compared: relative MSE.
  double rel_H = 0, rel_K = 0;
  std::size_t pixels = 0;  ///< pixels estimated and seeing a triangle
};

struct PullBackStep {
  double distance = 0;  ///< camera distance / the distance at which the mesh fills the picture
  double coverage = 0;  ///< fraction of the image's pixels that see the mesh
  std::vector<PullBackError> errors;  ///< one per estimator, in the order given
};

/// Runs the protocol: `object` is the mesh's per-vertex curvature (the paper uses its 3-edge
/// estimator, curvature::Estimator::prantl3) with its normals, which the rasteriser interpolates
/// into the G-buffer. Each of `estimators` is run on every step's G-buffer (on `device`, or the
/// double-precision reference when null). Mellado's K is not compared (mse_K 0).
/// @throw Error for a mesh without triangles, a field that does not match it, or bad options
std::vector<PullBackStep> pull_back(const Mesh& mesh, const curvature::CurvatureField& object,
                                    const std::vector<ScreenOptions>& estimators, Device* device,
                                    const PullBackOptions& options = {});

}  // namespace isocurv::screen
