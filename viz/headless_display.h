#pragma once
// An X display for VTK: Debian's VTK 9.1 renders through GLX even offscreen, so it needs one.
// Tested in tests/viz/test_render.cpp.

class vtkRenderWindow;

namespace isocurv::viz {

/// What the display is for: an offscreen picture can fall back to a private Xvfb, an interactive
/// window cannot (nobody would see it).
enum class DisplayUse { offscreen, interactive };

/// Makes sure VTK can open a render window: when DISPLAY names a display that XOpenDisplay can
/// open, does nothing. Otherwise (DISPLAY unset, or naming a display that cannot be opened, where
/// VTK would abort with "bad X server connection") for offscreen use starts a private Xvfb
/// (`Xvfb -displayfd ... -screen 0 1280x1024x24 -nolisten tcp`, which picks a free display number
/// itself and reports it once it accepts connections), sets DISPLAY in this process, and stops
/// the server at exit (it also dies with the calling thread, so call it from the main thread).
/// Idempotent and thread-safe. Throws Error naming the display for interactive use, or when Xvfb
/// cannot be started ("... apt-get install xvfb").
void ensure_display(DisplayUse use = DisplayUse::offscreen);

/// Checks that `window` can get an OpenGL context on the current display (VTK would otherwise abort
/// on the first render); throws Error naming the display when it cannot. Cached per process.
void check_opengl(vtkRenderWindow* window);

/// True when ensure_display() started a private Xvfb in this process.
bool using_private_display();

}  // namespace isocurv::viz
