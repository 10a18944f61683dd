#pragma once
// The interactive isosurface explorer: a VTK window with the surface coloured by curvature and an
// isovalue slider, and a time slider for a series (of volumes, or of meshes: then without the
// isovalue slider). It never extracts or reads anything itself: the caller supplies a callback
// that turns an isovalue into a surface (the app composes mc::extract and curvature::estimate, or
// reads a series' mesh file). The parts are in viz/detail/ (internal).
// Tested in tests/viz/explorer_fixture.h, tests/viz/test_explorer.cpp.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "lines/polylines.h"
#include "viz/render_options.h"
#include "viz/screen_image.h"

namespace isocurv::viz {

/// What the callback returns for one isovalue.
struct Surface {
  Mesh mesh;
  curvature::CurvatureField field;
  double update_ms = 0;  ///< time the callback spent (shown on screen; measured here when 0)
  std::string detail;    ///< optional extra text for the status line (e.g. "extract 12 ms, 340 bricks")
};

/// One step of a scripted run (for tests and demos), executed on a timer inside the event loop.
struct ExplorerAction {
  enum class Kind { SetIsovalue, Key, Type, Screenshot, Resize, SetFrame, Status, Wait };
  Kind kind = Kind::Key;
  float isovalue = 0;  ///< SetIsovalue: moves the slider there, as a user would
  char key = 0;        ///< Key: a key press ('c', 'a', 'd', 's', 'r', '\r' for Enter, ...)
  /// Screenshot: PNG path; Status: the text file the status line's text is written to (a test
  /// reads the frame label there); Type: the characters typed, one key each
  std::string path;
  int width = 0, height = 0;  ///< Resize: the window's new size
  int frame = 0;              ///< SetFrame: moves the time slider there, as a user would

  static ExplorerAction set_isovalue(float iso) { return {Kind::SetIsovalue, iso, 0, {}, 0, 0}; }
  static ExplorerAction press(char key) { return {Kind::Key, 0, key, {}, 0, 0}; }
  static ExplorerAction type(std::string text) { return {Kind::Type, 0, 0, std::move(text), 0, 0}; }
  static ExplorerAction screenshot(std::string path) { return {Kind::Screenshot, 0, 0, std::move(path), 0, 0}; }
  static ExplorerAction resize(int w, int h) { return {Kind::Resize, 0, 0, {}, w, h}; }
  static ExplorerAction set_frame(int f) { return {Kind::SetFrame, 0, 0, {}, 0, 0, f}; }
  static ExplorerAction status(std::string path) { return {Kind::Status, 0, 0, std::move(path), 0, 0}; }
  static ExplorerAction wait() { return {Kind::Wait, 0, 0, {}, 0, 0}; }  ///< one tick, nothing done
};

/// The explorer's screen-space mode ('x'; SEEDS-SPEC 4.4): curvature per pixel of the surface as
/// the camera sees it, cast from the volume (or rasterised from a mesh file shown) instead of
/// extracted, and shown in place of the mesh. The isovalue slider then re-casts; so does every
/// camera move. Both run at 1/2 or 1/4 resolution while the mouse drags (the slider or the
/// camera) when a full image takes longer than the live-update limit, then at full resolution
/// on release.
struct ScreenMode {
  /// The image for `camera` at width x height pixels (the surface part of the window, or a
  /// fraction of it): of the volume's isosurface at `iso` when `mesh` is null, else of that mesh
  /// (a mesh file opened with 'o'). May throw Error: the previous image then stays.
  /// Unset: 'x' says that screen space is not available.
  std::function<ScreenImage(float iso, const Surface* mesh, const Camera& camera, int width,
                            int height)>
      image;
  /// The box (xmin, xmax, ymin, ymax, zmin, zmax) of the volume's surface at `iso`: it frames the
  /// camera while no mesh has been extracted (start_on). Unset or false: the unit box.
  std::function<bool(float iso, std::array<double, 6>& bounds)> bounds;
  bool start_on = false;  ///< open in screen-space mode: nothing is extracted until 'x' leaves it
  /// When set: the title in screen-space mode (as ExplorerSetup::title_for).
  std::function<std::string(float iso, const std::string& quantity)> title_for;
};

/// Everything the explorer needs.
struct ExplorerSetup {
  float isovalue = 0;                       ///< initial isovalue
  float min_value = 0, max_value = 1;       ///< slider range (the volume's value range)
  std::function<Surface(float iso)> surface;  ///< re-extracts and re-estimates; may throw Error
  /// False for surfaces that no isovalue makes (a series of mesh files): no isovalue slider, 'i'
  /// is refused, the status line names the frame instead of an isovalue, screen-space mode
  /// rasterises the mesh shown, and surface() gets `isovalue` (to ignore); min_value and
  /// max_value are not used.
  bool has_isovalue = true;
  /// 'o': reads a mesh file (with curvature estimated when it carries none); may throw Error.
  /// Unset: 'o' says that opening is not available.
  std::function<Surface(const std::string& path)> open_mesh;
  /// 'w': writes the surface shown, with its arrays; may throw Error. Unset: not available.
  std::function<void(const std::string& path, const Mesh&, const curvature::CurvatureField&)> save_surface;
  RenderOptions view;                       ///< initial colour, shading, glyphs, window size, title
  /// When set: the title for the surface at `iso` coloured by `quantity` (shown after each
  /// change of either).
  std::function<std::string(float iso, const std::string& quantity)> title_for;
  std::string screenshot_prefix = "isocurv-screenshot";  ///< 's' writes <prefix>-NNN.png
  std::string camera_path = "isocurv-camera.json";       ///< 'k' writes the camera here (--camera)
  std::string surface_path = "isocurv-surface.vtp";      ///< 'w' proposes this path
  /// Feature lines of the surface shown as `camera` sees it, drawn while the 'l' key has them on
  /// and recomputed before a frame whenever the camera moved or the surface changed since the
  /// last call (`surface_changed` false: only the camera moved). Empty: 'l' does nothing.
  std::function<lines::Polylines(const Surface& surface, const Camera& camera, bool surface_changed)> lines;
  bool show_lines = false;  ///< lines on from the start (needs `lines`)
  /// A time series (isocurv view --time-series): with frames >= 2 a time slider (frames 0 ..
  /// frames - 1) appears above the isovalue slider and space plays / pauses (play_fps frames a
  /// second at most, wrapping around). Changing the frame calls set_frame(k), which makes frame k
  /// current (may throw Error: the previous frame then stays), then surface(iso) at the current
  /// isovalue.
  int frames = 0;
  std::function<void(int frame)> set_frame;
  double play_fps = 10;
  /// When set: the text the status line shows for frame k (e.g. its file and time).
  std::function<std::string(int frame)> frame_label;
  /// Frames share their colour ranges, so that an animation does not flicker (a mesh series):
  /// each array's range is the one the first frame gives it (the range render would use for that
  /// frame alone), held for every frame; an array the first frame lacks takes its range from the
  /// frame it is first shown on. view.range (--range) wins when set; a mesh opened with 'o' and
  /// screen-space images keep ranges of their own. False: each surface its own range.
  bool shared_color_range = false;
  ScreenMode screen;  ///< screen-space mode ('x'), when screen.image is set
  /// When non-empty: run these actions (one per timer tick, ~100 ms apart) and close the window.
  std::vector<ExplorerAction> script;
};

/// Opens the explorer and returns when its window is closed (or 'q'/'e' pressed, or the script is
/// done). The surface is framed beside the legend and above the status line and the isovalue
/// slider, which have a strip of their own. Keys: c cycles the colour through every point array of
/// the surface shown (H, K, k1, k2, ShapeIndex, Curvedness, AO, Unreliable, Boundary, then its
/// extra arrays: H_s2, LBE, H_ii, ...; a new surface without the array coloured goes back to
/// H), a toggles AO shading (lambert / ambient-ao), d toggles direction
/// glyphs, l toggles the feature lines (when setup.lines is given), x switches screen-space mode
/// on and off (setup.screen; there c alternates H and K), v cycles the named views (iso,
/// +x, -x, +y, -y, +z, -z) and r resets the camera to the current one, i types an isovalue, o types
/// a mesh file to open, w types a path to save the surface shown (proposing surface_path), k saves
/// the camera to camera_path, s saves a screenshot (name printed on stdout), space plays / pauses a
/// time series (setup.frames; a series of meshes has no isovalue slider, setup.has_isovalue).
/// While typing, Enter applies, Escape cancels, BackSpace deletes. The
/// mouse rotates, pans and zooms. Dragging the slider re-runs the callback live while updates take
/// under 150 ms, otherwise on release. A failed update (Error from the callback) is shown on the
/// status line and the previous surface stays. Interactive use needs an X display; a scripted run
/// starts a private Xvfb when there is none (ensure_display). Throws Error for a bad setup or when
/// the initial surface cannot be made.
void run_explorer(const ExplorerSetup& setup);

}  // namespace isocurv::viz
