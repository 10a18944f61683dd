#pragma once
// The explorer's internals (viz/explorer.h is the public side): one Explorer object owns the VTK
// window, the scene, the sliders and the state of one run_explorer call. Its members are defined
// by concern in viz/detail/explorer_*.cpp:
//   explorer_window.cpp      the window, its layout, resizing and the timer that drives the rest
//   explorer_surface.cpp     asking the callback for a surface, showing it, titles and options
//   explorer_range.cpp       colour ranges held across the frames of a series
//   explorer_isovalue.cpp    the isovalue slider
//   explorer_time.cpp        the time slider and play / pause of a series
//   explorer_keys.cpp        the keys, and typing an isovalue or a path
//   explorer_status.cpp      the status line
//   explorer_camera.cpp      named views, resetting and saving the camera
//   explorer_screen.cpp      screen-space mode ('x')
//   explorer_lines.cpp       the feature-line overlay ('l')
//   explorer_screenshot.cpp  screenshots ('s' and scripts)
//   explorer_script.cpp      scripted runs (ExplorerSetup::script)
#include <cstddef>
#include <map>
#include <string>

#include <vtkCallbackCommand.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkSliderWidget.h>
#include <vtkTextActor.h>

#include "core/camera.h"
#include "viz/curvature_scene.h"
#include "viz/explorer.h"
#include "viz/line_overlay.h"

namespace isocurv::viz::detail {

constexpr double kLiveUpdateMs = 150;  // slower updates wait for the slider's release
constexpr unsigned long kScriptTickMs = 100;
constexpr double kStatusFontPerPixel = 1.0 / 48;  // status font per pixel of the window height
constexpr int kStatusLines = 4;
constexpr double kSliderBand = 0.07;  // of the window height, above the status
constexpr char kEnter = '\r', kEscape = 27, kBackSpace = 8, kDelete = 127;

class Explorer;

/// Trackball camera, with c/a/d/s routed to the explorer (VTK's own 's' would switch to surface
/// representation, 'a'/'c' to actor/camera modes in other styles).
class ExplorerStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static ExplorerStyle* New();
  vtkTypeMacro(ExplorerStyle, vtkInteractorStyleTrackballCamera);
  void OnChar() override;
  Explorer* explorer = nullptr;
};

class Explorer {
 public:
  explicit Explorer(const ExplorerSetup& setup) : setup_(setup) {}

  /// Opens the window and runs the event loop until it is closed or the script is done.
  void run();  // explorer_window.cpp

  /// Key handling shared by the keyboard and scripts; false when the key is not ours.
  bool on_key(char key);  // explorer_keys.cpp

 private:
  enum class Entry { none, isovalue, open, save };
  static constexpr int kNamedViews = 7;

  // explorer_window.cpp
  /// Lays out the window: the status line and slider in a strip at the bottom, the legend on the
  /// right, the surface in the rest.
  void relayout(int width, int height);
  static void on_resize(vtkObject*, unsigned long, void* self, void*);
  static void on_timer(vtkObject*, unsigned long, void* self, void* data);

  // explorer_keys.cpp
  void start_entry(Entry e, const std::string& initial);
  /// A key while typing: Enter applies, Escape cancels, BackSpace deletes, others are text.
  void typed(char key);

  // explorer_camera.cpp
  void reset_camera();
  /// Frames the mesh shown, or while there is none (screen-space mode from the start) the box of
  /// the volume's surface.
  void frame_camera();
  void save_camera_file();

  // explorer_surface.cpp
  /// The title for `iso` and `quantity`, in screen-space mode or not.
  std::string title(float iso, const std::string& quantity, bool screen) const;
  Surface call(float iso);
  void note_update(const Surface& s);
  void retitle();
  bool try_options(RenderOptions o);
  /// Shows `s` (a frame of the series, or the volume's surface, when `frame`; else an opened
  /// mesh file); when it lacks the array coloured now (an extra of an opened mesh, say) the
  /// colour goes back to H first, and the status line says so.
  std::string show_surface(const Surface& s, bool frame);
  /// Shows `s`, the volume's surface (`file` empty) or that mesh file's, and notes its update.
  void present(const Surface& s, const std::string& file);

  /// True when the surface shown is a mesh rather than a volume's isosurface: a mesh file opened
  /// with 'o', or a frame of a mesh series. Screen-space mode rasterises it then.
  bool shows_mesh() const { return !shown_.empty() || !setup_.has_isovalue; }

  // explorer_range.cpp
  /// True when held ranges apply to the surface shown now (`frame`: a frame, not an opened file).
  bool holds_ranges(bool frame) const;
  /// `o` with the range it should colour with: the held range of its colour when holds_ranges,
  /// else view.range (--range, or automatic).
  RenderOptions ranged(RenderOptions o, bool frame) const;
  /// After options or a surface were applied: holds the scene's range for the colour shown when
  /// holds_ranges and none is held for it yet.
  void hold_range(bool frame);
  /// Holds the range of every array of the first frame (shown now), as the scene computes it.
  void hold_first_frame_ranges();

  // explorer_isovalue.cpp
  void make_slider();
  float slider_value() const;
  static void on_slider(vtkObject*, unsigned long event, void* self, void*);
  /// Re-extracts at `iso`; on failure keeps the previous surface and reports on the status line.
  void update(float iso);

  // explorer_time.cpp
  bool has_time() const;
  /// Makes frame k current and re-extracts at the current isovalue; on failure keeps the frame
  /// shown and reports on the status line (and stops playing).
  void go_to_frame(int k);
  void make_time_slider();
  static void on_time_slider(vtkObject*, unsigned long event, void* self, void*);
  /// The play timer ticked: the next frame while playing (and nothing is being typed).
  void play_tick();

  // explorer_status.cpp
  static std::string format(double v);
  static std::string format_ms(double ms);
  void refresh_status();
  /// Writes the status line's text to `path` (a script's Status action); an error goes to the
  /// status line.
  void write_status(const std::string& path);

  // explorer_screen.cpp
  /// The colour screen-space mode starts with: `color` when it is H or K, else H.
  static std::string screen_quantity(const std::string& color);
  void enter_screen();
  /// Back to the mesh: extracted first when the isovalue moved in screen-space mode (on failure
  /// the mode stays on, with the error on the status line).
  void leave_screen();
  /// The same view to within rounding (VTK re-derives parts of its camera while rendering).
  static bool same_camera(const Camera& a, const Camera& b);
  /// Casts the screen-space image at `iso` (of the mesh file shown when `of_mesh`, else of the
  /// volume) for the camera now, at the surface box's size divided by `scale`, and shows it;
  /// false, with the error on the status line, when the callback fails (the old image stays).
  bool cast(float iso, bool of_mesh, int scale = 1);
  /// Before each frame in screen-space mode: a new image when the camera, the box or the
  /// resolution wanted changed (coarser while the mouse drags and a full image is slow).
  static void on_overlay_start(vtkObject*, unsigned long, void* self, void*);
  /// The resolution divisor while the mouse drags (the camera or the slider): 1 while a full
  /// image takes at most the live-update limit, else 2, or 4 beyond four times it.
  int coarse_scale() const;
  /// The slider moved in screen-space mode: re-cast, coarsely while it is dragged (`live`) and a
  /// full image is slow, in full on release.
  void slide_screen(float iso, bool live);
  static void on_interaction(vtkObject*, unsigned long event, void* self, void*);
  /// A new screen-space image of the volume is shown: the mesh, if any, is of another isovalue
  /// or frame now.
  void note_cast();

  // explorer_lines.cpp
  /// Before each frame: new lines when they are on and the camera or the surface changed.
  static void on_render_start(vtkObject*, unsigned long, void* self, void*);

  // explorer_screenshot.cpp
  std::string next_screenshot_name();
  void screenshot(const std::string& path);

  // explorer_script.cpp
  /// Runs the script's next action (or ends the run after the last).
  void step();

  const ExplorerSetup& setup_;
  CurvatureScene scene_;
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderWindowInteractor> interactor_;
  vtkNew<ExplorerStyle> style_;
  vtkNew<vtkSliderWidget> slider_;
  vtkNew<vtkSliderWidget> time_slider_;  // frames of a time series (setup.frames >= 2)
  vtkNew<vtkCallbackCommand> time_callback_;
  int frame_ = 0;         // frame shown
  bool playing_ = false;  // space
  int play_timer_ = -1, script_timer_ = -1;
  vtkNew<vtkTextActor> status_;
  vtkNew<vtkCallbackCommand> slider_callback_;
  vtkNew<vtkCallbackCommand> timer_callback_;
  vtkNew<vtkCallbackCommand> resize_callback_;
  Surface current_;    // the surface shown (for 'w' and the lines)
  std::string shown_;  // the mesh file shown, empty for the volume's isosurface
  NamedView view_ = NamedView::iso;
  Entry entry_ = Entry::none;  // what is being typed
  std::string typed_;
  vtkNew<vtkCallbackCommand> render_start_;
  // Screen-space mode ('x')
  vtkNew<vtkCallbackCommand> cast_start_;   // the overlay's StartEvent: re-cast when needed
  vtkNew<vtkCallbackCommand> interaction_;  // the style's Start/EndInteractionEvent
  bool screen_on_ = false;
  bool mesh_stale_ = false;   // the mesh shown is not of iso_ (moved in screen-space mode)
  bool image_stale_ = true;   // cast before the next frame
  bool interacting_ = false;  // the mouse drags the camera
  bool sliding_ = false;      // the mouse drags the isovalue slider (screen-space mode)
  Camera cast_camera_;        // what the image shown was cast for
  int cast_w_ = 0, cast_h_ = 0, cast_scale_ = 1;
  double full_ms_ = 0;  // the last full-resolution cast
  std::size_t pixels_ = 0, image_pixels_ = 0;
  LineOverlay overlay_;
  bool lines_on_ = false;
  bool lines_surface_stale_ = true;     // the surface changed since the lines were made
  vtkMTimeType lines_camera_time_ = 0;  // the camera's MTime when they were made
  float iso_ = 0;                       // isovalue of the surface shown
  float attempted_ = 0;                 // last isovalue the callback was asked for
  std::size_t vertices_ = 0, triangles_ = 0;
  double last_ms_ = 0;
  std::string detail_, message_;
  std::map<std::string, ColorRange> held_ranges_;  // by array: setup.shared_color_range
  std::size_t next_action_ = 0;
  int screenshots_ = 0;
};

}  // namespace isocurv::viz::detail
