#pragma once
// A Camera saved as JSON (the explorer's 'k' key) and loaded again (--camera FILE).
//
// The file: {"position": [x, y, z], "focal_point": [x, y, z], "view_up": [x, y, z],
// "ortho": false, "view_angle_deg": 30, "parallel_scale": 1} in world units.
// Tested in tests/viz/test_explorer.cpp.
#include <string>

#include "core/camera.h"

namespace isocurv::viz {

/// Writes `cam` to `path` atomically. @throw Error naming the file when it cannot be written.
void save_camera(const std::string& path, const Camera& cam);

/// Reads a camera written by save_camera. @throw Error naming the file for a missing or
/// malformed file, a missing or non-finite field, position equal to focal_point, a view up
/// parallel to the view direction, a view angle outside (0, 180) or a parallel scale <= 0.
Camera load_camera(const std::string& path);

}  // namespace isocurv::viz
