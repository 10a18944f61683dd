#pragma once
// An X display for VTK: Debian's VTK 9.1 renders through GLX even offscreen, so it needs one.

class vtkRenderWindow;

namespace isocurv::viz {

/// Makes sure VTK can open a render window. When DISPLAY is set, does nothing. Otherwise starts a
/// private Xvfb (`Xvfb -displayfd ... -screen 0 1280x1024x24 -nolisten tcp`, which picks a free
/// display number itself and reports it once it accepts connections), sets DISPLAY in this
/// process, and stops the server at exit (it also dies with the calling thread, so call it from
/// the main thread). Idempotent and thread-safe. Throws
/// Error("no X display and Xvfb could not be started: apt-get install xvfb") when that fails.
void ensure_display();

/// Checks that `window` can get an OpenGL context on the current display (VTK would otherwise abort
/// on the first render); throws Error naming the display when it cannot. Cached per process.
void check_opengl(vtkRenderWindow* window);

/// True when ensure_display() started a private Xvfb in this process.
bool using_private_display();

}  // namespace isocurv::viz
