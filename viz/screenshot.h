#pragma once
// Saving what a render window shows as a PNG.
// Tested through every picture written: tests/viz/test_render.cpp,
// tests/viz/test_explorer_view.cpp.
#include <string>

class vtkRenderWindow;

namespace isocurv::viz {

/// Renders `window` and writes its RGB pixels to `path` as a PNG, atomically (vtkPNGWriter writes
/// a temporary name that is then renamed). Throws Error naming `path` on failure.
void save_png(vtkRenderWindow* window, const std::string& path);

}  // namespace isocurv::viz
