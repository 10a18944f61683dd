#pragma once
// How a curvature surface is shown: shared by render_png and the explorer.
#include <string>

#include "core/camera.h"

namespace isocurv::viz {

/// What to show and how.
struct RenderOptions {
  std::string color = "H";        ///< colour quantity: H, K, k1, k2, ShapeIndex, Curvedness or AO
  bool ao = false;                ///< multiply the vertex colours by the AO array
  bool dirs = false;              ///< draw principal-direction glyphs (dir1 white, dir2 black)
  int width = 1024, height = 768; ///< image (or window) size in pixels
  double clamp_percentile = 2;    ///< colour range ignores this percentage of extreme values (color_range)
  std::string title;              ///< text at the top of the image; none when empty
  ViewSpec view;                  ///< viewpoint, turns, zoom and projection (fit_camera)
};

}  // namespace isocurv::viz
