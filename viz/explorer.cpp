#include "viz/explorer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSliderRepresentation2D.h>
#include <vtkProperty2D.h>
#include <vtkSliderWidget.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include "core/error.h"
#include "viz/camera_file.h"
#include "viz/curvature_scene.h"
#include "viz/headless_display.h"
#include "viz/line_overlay.h"
#include "viz/quantity.h"
#include "viz/screenshot.h"

namespace isocurv::viz {
namespace {

constexpr double kLiveUpdateMs = 150;  // slower updates wait for the slider's release
constexpr unsigned long kScriptTickMs = 100;
constexpr double kStatusFontPerPixel = 1.0 / 48;  // status font per pixel of the window height
constexpr int kStatusLines = 4;
constexpr double kSliderBand = 0.07;              // of the window height, above the status
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
vtkStandardNewMacro(ExplorerStyle);

class Explorer {
 public:
  explicit Explorer(const ExplorerSetup& setup) : setup_(setup) {}

  void run() {
    const bool start_screen = setup_.screen.start_on && setup_.screen.image;
    iso_ = attempted_ = setup_.isovalue;
    RenderOptions first_options = setup_.view;
    if (start_screen) {
      mesh_stale_ = true;  // nothing extracted yet
      first_options.color = screen_quantity(first_options.color);
      first_options.title = title(iso_, first_options.color, true);
      scene_.set_options(first_options);
      scene_.set_image_mode(true);
      screen_on_ = true;
    } else {
      Surface first = call(setup_.isovalue);  // throws: no window without a first surface
      scene_.set_options(first_options);
      scene_.set_surface(first.mesh, first.field);
      note_update(first);
    }
    view_ = setup_.view.view.view;

    window_->SetSize(setup_.view.width, setup_.view.height);
    window_->SetWindowName(("isocurv explorer" + (setup_.view.title.empty() ? "" : " - " + setup_.view.title)).c_str());
    check_opengl(window_);
    scene_.attach(window_);
    interactor_->SetRenderWindow(window_);
    style_->explorer = this;
    interactor_->SetInteractorStyle(style_);
    style_->SetDefaultRenderer(scene_.renderer());

    status_->GetTextProperty()->SetColor(1, 1, 1);
    status_->GetTextProperty()->SetVerticalJustificationToBottom();
    status_->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    status_->GetPositionCoordinate()->SetValue(0.01, 0.01);  // bottom left, under the slider
    scene_.overlay()->AddViewProp(status_);
    make_slider();
    if (has_time()) make_time_slider();
    relayout(setup_.view.width, setup_.view.height);
    if (setup_.screen.image) {
      // The overlay renders first (layer 0): a new image is in place before anything is drawn.
      cast_start_->SetCallback(&Explorer::on_overlay_start);
      cast_start_->SetClientData(this);
      scene_.overlay()->AddObserver(vtkCommand::StartEvent, cast_start_);
      interaction_->SetCallback(&Explorer::on_interaction);
      interaction_->SetClientData(this);
      style_->AddObserver(vtkCommand::StartInteractionEvent, interaction_);
      style_->AddObserver(vtkCommand::EndInteractionEvent, interaction_);
    }
    if (setup_.lines) {
      lines_on_ = setup_.show_lines;
      overlay_.add_to(scene_.renderer());
      overlay_.set_visible(lines_on_ && !screen_on_);
      render_start_->SetCallback(&Explorer::on_render_start);
      render_start_->SetClientData(this);
      scene_.renderer()->AddObserver(vtkCommand::StartEvent, render_start_);
    }
    frame_camera();
    refresh_status();
    resize_callback_->SetCallback(&Explorer::on_resize);
    resize_callback_->SetClientData(this);
    window_->AddObserver(vtkCommand::WindowResizeEvent, resize_callback_);

    interactor_->Initialize();
    slider_->EnabledOn();
    if (has_time()) time_slider_->EnabledOn();
    if (!setup_.script.empty() || has_time()) {
      timer_callback_->SetCallback(&Explorer::on_timer);
      timer_callback_->SetClientData(this);
      interactor_->AddObserver(vtkCommand::TimerEvent, timer_callback_);
    }
    if (!setup_.script.empty()) script_timer_ = interactor_->CreateRepeatingTimer(kScriptTickMs);
    if (has_time())
      play_timer_ = interactor_->CreateRepeatingTimer(
          static_cast<unsigned long>(1000.0 / std::max(0.5, std::min(120.0, setup_.play_fps))));
    window_->Render();
    interactor_->Start();
    slider_->EnabledOff();
    if (has_time()) time_slider_->EnabledOff();
    window_->Finalize();
  }

  /// Key handling shared by the keyboard and scripts; false when the key is not ours.
  bool on_key(char key) {
    if (entry_ != Entry::none) {
      typed(key);
      refresh_status();
      window_->Render();
      return true;
    }
    RenderOptions o = scene_.options();
    if (screen_on_ && (key == 'a' || key == 'd' || (key == 'l' && setup_.lines))) {
      message_ = std::string("'") + key + "' applies to the mesh: x leaves screen-space mode";
      refresh_status();
      window_->Render();
      return true;
    }
    switch (key) {
      case 'c': {  // every point array of the surface shown: the curvature ones, then its extras
        const std::vector<std::string> q =
            screen_on_ ? std::vector<std::string>{"H", "K"} : field_quantities(current_.field);
        auto it = std::find(q.begin(), q.end(), canonical_quantity(o.color));
        for (std::size_t step = 0; step < q.size(); ++step) {
          it = (it == q.end() || it + 1 == q.end()) ? q.begin() : it + 1;
          o.color = *it;
          if (try_options(o)) break;
        }
        break;
      }
      case 'a':
        o.shading = o.shading == Shading::lambert ? Shading::ambient_ao : Shading::lambert;
        try_options(o);
        break;
      case 'd': o.dirs = !o.dirs; try_options(o); break;
      case 's': screenshot(next_screenshot_name()); break;
      case 'v':
        view_ = static_cast<NamedView>((static_cast<int>(view_) + 1) % kNamedViews);
        reset_camera();
        break;
      case 'r': reset_camera(); break;
      case 'i': start_entry(Entry::isovalue, ""); break;
      case 'o':
        if (setup_.open_mesh) start_entry(Entry::open, "");
        else message_ = "opening meshes is not available here";
        break;
      case 'w':
        if (setup_.save_surface && screen_on_ && mesh_stale_)
          message_ = "no mesh of this isovalue yet: x leaves screen-space mode and extracts it";
        else if (setup_.save_surface)
          start_entry(Entry::save, setup_.surface_path);
        else message_ = "saving the surface is not available here";
        break;
      case 'k': save_camera_file(); break;
      case 'x':
        if (!setup_.screen.image)
          message_ = "screen space is not available here";
        else if (screen_on_)
          leave_screen();
        else
          enter_screen();
        break;
      case ' ':
        if (!has_time()) return false;
        playing_ = !playing_;
        refresh_status();
        window_->Render();
        break;
      case 'l':
        if (!setup_.lines) return false;
        lines_on_ = !lines_on_;
        overlay_.set_visible(lines_on_);
        break;
      default: return false;
    }
    refresh_status();
    window_->Render();
    return true;
  }

 private:
  enum class Entry { none, isovalue, open, save };
  static constexpr int kNamedViews = 7;

  void start_entry(Entry e, const std::string& initial) {
    entry_ = e;
    typed_ = initial;
    message_.clear();
  }

  /// A key while typing: Enter applies, Escape cancels, BackSpace deletes, others are text.
  void typed(char key) {
    if (key == kEscape) {
      entry_ = Entry::none;
      return;
    }
    if (key == kBackSpace || key == kDelete) {
      if (!typed_.empty()) typed_.pop_back();
      return;
    }
    if (key != kEnter && key != '\n') {
      if (key >= 32 && key < 127) typed_.push_back(key);
      return;
    }
    const Entry e = entry_;
    entry_ = Entry::none;
    if (e == Entry::isovalue) {
      char* end = nullptr;
      const double v = std::strtod(typed_.c_str(), &end);
      if (typed_.empty() || *end != '\0' || !std::isfinite(v)) {
        message_ = "not a number: '" + typed_ + "'";
      } else if (v < setup_.min_value || v > setup_.max_value) {
        message_ = "isovalue " + format(v) + " is outside the value range [" + format(setup_.min_value) + ", " +
                   format(setup_.max_value) + "]";
      } else {
        static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation())->SetValue(v);
        update(static_cast<float>(v));
      }
    } else if (e == Entry::open) {
      try {
        present(setup_.open_mesh(typed_), typed_);
        image_stale_ = true;  // screen-space mode: the image is now the mesh's
        reset_camera();
      } catch (const Error& err) {
        message_ = err.what();
      }
    } else if (e == Entry::save) {
      try {
        setup_.save_surface(typed_, current_.mesh, current_.field);
        message_ = "saved the surface to " + typed_;
        std::cout << "saved surface: " << typed_ << std::endl;
      } catch (const Error& err) {
        message_ = err.what();
      }
    }
  }

  void reset_camera() {
    RenderOptions o = scene_.options();
    o.view.view = view_;
    o.camera.reset();
    try_options(o);
    frame_camera();
  }

  /// Frames the mesh shown, or while there is none (screen-space mode from the start) the box of
  /// the volume's surface.
  void frame_camera() {
    std::array<double, 6> b{};
    if (current_.mesh.positions.empty() && screen_on_ && setup_.screen.bounds &&
        setup_.screen.bounds(iso_, b))
      scene_.frame_camera(&b);
    else
      scene_.frame_camera();
  }

  /// The title for `iso` and `quantity`, in screen-space mode or not.
  std::string title(float iso, const std::string& quantity, bool screen) const {
    if (screen && setup_.screen.title_for) return setup_.screen.title_for(iso, quantity);
    if (setup_.title_for) return setup_.title_for(iso, quantity);
    return setup_.view.title;
  }

  /// The colour screen-space mode starts with: `color` when it is H or K, else H.
  static std::string screen_quantity(const std::string& color) {
    const std::string q = canonical_quantity(color);
    return q == "H" || q == "K" ? q : "H";
  }

  void enter_screen() {
    RenderOptions o = scene_.options();
    o.color = screen_quantity(o.color);
    o.title = title(iso_, o.color, true);
    try {
      scene_.set_options(o);
      scene_.set_image_mode(true);
    } catch (const Error& e) {
      message_ = e.what();
      return;
    }
    screen_on_ = true;
    image_stale_ = true;  // cast before the next frame is drawn
    overlay_.set_visible(false);
    message_.clear();
  }

  /// Back to the mesh: extracted first when the isovalue moved in screen-space mode (on failure
  /// the mode stays on, with the error on the status line).
  void leave_screen() {
    if (mesh_stale_) {
      Surface s;
      try {
        s = call(iso_);
      } catch (const Error& e) {
        message_ = "isovalue " + format(iso_) + ": " + e.what();
        return;
      }
      scene_.set_image_mode(false);
      screen_on_ = false;
      present(s, "");
      attempted_ = iso_;
    } else {
      scene_.set_image_mode(false);
      screen_on_ = false;
      vertices_ = current_.mesh.vertex_count();
      triangles_ = current_.mesh.triangle_count();
    }
    overlay_.set_visible(lines_on_);
    lines_surface_stale_ = true;
    retitle();
  }

  /// The same view to within rounding (VTK re-derives parts of its camera while rendering).
  static bool same_camera(const Camera& a, const Camera& b) {
    double scale = 1e-300, diff = 0;
    for (int k = 0; k < 3; ++k) {
      scale = std::max(scale, std::abs(a.position[k] - a.focal_point[k]));
      diff = std::max({diff, std::abs(a.position[k] - b.position[k]),
                       std::abs(a.focal_point[k] - b.focal_point[k])});
    }
    double up = 0;
    for (int k = 0; k < 3; ++k) up = std::max(up, std::abs(a.view_up[k] - b.view_up[k]));
    constexpr double kTolerance = 1e-6;  // VTK's view angle drifts by ~3e-8
    return a.ortho == b.ortho && diff <= kTolerance * scale && up <= kTolerance &&
           std::abs(a.view_angle_deg - b.view_angle_deg) <= kTolerance * a.view_angle_deg &&
           std::abs(a.parallel_scale - b.parallel_scale) <= kTolerance * a.parallel_scale;
  }

  /// Casts the screen-space image at `iso` (of the mesh file shown when `of_mesh`, else of the
  /// volume) for the camera now, at the surface box's size divided by `scale`, and shows it;
  /// false, with the error on the status line, when the callback fails (the old image stays).
  bool cast(float iso, bool of_mesh, int scale = 1) {
    const PixelBox& box = scene_.layout().surface;
    const int w = box.x1 - box.x0, h = box.y1 - box.y0;
    cast_camera_ = scene_.current_camera();
    cast_w_ = w, cast_h_ = h, cast_scale_ = scale;
    image_stale_ = false;
    if (w < 1 || h < 1) return false;
    const int cw = (w + scale - 1) / scale, ch = (h + scale - 1) / scale;
    try {
      const auto start = std::chrono::steady_clock::now();
      ScreenImage img =
          setup_.screen.image(iso, of_mesh ? &current_ : nullptr, cast_camera_, cw, ch);
      if (img.update_ms <= 0)
        img.update_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
      if (img.width != cw || img.height != ch)
        throw Error("the image is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                    " pixels, not the " + std::to_string(cw) + "x" + std::to_string(ch) +
                    " asked for");
      scene_.set_image(img, scale);
      last_ms_ = img.update_ms;
      if (scale == 1) full_ms_ = img.update_ms;
      detail_ = img.detail;
      pixels_ = img.valid_count();
      image_pixels_ = img.pixels();
      return true;
    } catch (const Error& e) {
      message_ = std::string("screen space: ") + e.what();
      return false;
    }
  }

  /// Before each frame in screen-space mode: a new image when the camera, the box or the
  /// resolution wanted changed (coarser while the mouse drags and a full image is slow).
  static void on_overlay_start(vtkObject*, unsigned long, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    if (!e->screen_on_) return;
    const PixelBox& box = e->scene_.layout().surface;
    const int scale = e->interacting_ || e->sliding_ ? e->coarse_scale() : 1;
    if (!e->image_stale_ && same_camera(e->scene_.current_camera(), e->cast_camera_) &&
        box.x1 - box.x0 == e->cast_w_ && box.y1 - box.y0 == e->cast_h_ && scale == e->cast_scale_)
      return;
    e->cast(e->iso_, !e->shown_.empty(), scale);
    e->refresh_status();
  }

  /// The resolution divisor while the mouse drags (the camera or the slider): 1 while a full
  /// image takes at most the live-update limit, else 2, or 4 beyond four times it.
  int coarse_scale() const {
    return full_ms_ <= kLiveUpdateMs ? 1 : full_ms_ <= 4 * kLiveUpdateMs ? 2 : 4;
  }

  /// The slider moved in screen-space mode: re-cast, coarsely while it is dragged (`live`) and a
  /// full image is slow, in full on release.
  void slide_screen(float iso, bool live) {
    sliding_ = live;
    const int scale = live ? coarse_scale() : 1;
    if (iso == attempted_ && scale == cast_scale_) return;
    attempted_ = iso;
    if (cast(iso, false, scale)) {
      iso_ = iso;
      note_cast();
      retitle();
    } else {
      message_ = "isovalue " + format(iso) + ": " + message_;
    }
    refresh_status();
    window_->Render();
  }

  static void on_interaction(vtkObject*, unsigned long event, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    e->interacting_ = event == vtkCommand::StartInteractionEvent;
    if (!e->interacting_ && e->screen_on_ && e->cast_scale_ > 1)
      e->window_->Render();  // full image
  }

  void save_camera_file() {
    try {
      save_camera(setup_.camera_path, scene_.current_camera());
      message_ = "saved the camera to " + setup_.camera_path + " (isocurv render --camera)";
      std::cout << "saved camera: " << setup_.camera_path << std::endl;
    } catch (const Error& e) {
      message_ = e.what();
    }
  }

  /// Lays out the window: the status line and slider in a strip at the bottom, the legend on the
  /// right, the surface in the rest.
  void relayout(int width, int height) {
    const int font = std::max(11, static_cast<int>(height * kStatusFontPerPixel));
    status_->GetTextProperty()->SetFontSize(font);
    const int status_px = static_cast<int>((kStatusLines + (has_time() ? 1 : 0)) * font * 1.25);
    const int slider_px = std::max(static_cast<int>(kSliderBand * height), 2 * font);
    scene_.set_size(width, height);
    scene_.set_bottom_reserved(status_px + slider_px * (has_time() ? 2 : 1));
    auto* rep = static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation());
    const double y = (status_px + 0.5 * slider_px) / double(height);
    const double right = scene_.layout().surface.x1 / double(width);
    rep->GetPoint1Coordinate()->SetValue(0.08, y);
    rep->GetPoint2Coordinate()->SetValue(std::max(0.3, right - 0.08), y);
    if (has_time()) {  // the time slider in a band of its own above the isovalue's
      auto* t = static_cast<vtkSliderRepresentation2D*>(time_slider_->GetRepresentation());
      const double yt = (status_px + 1.5 * slider_px) / double(height);
      t->GetPoint1Coordinate()->SetValue(0.08, yt);
      t->GetPoint2Coordinate()->SetValue(std::max(0.3, right - 0.08), yt);
    }
  }

  static void on_resize(vtkObject*, unsigned long, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    const int* size = e->window_->GetSize();
    if (size[0] < 16 || size[1] < 16) return;
    if (size[0] == e->scene_.options().width && size[1] == e->scene_.options().height) return;
    e->relayout(size[0], size[1]);
  }

  Surface call(float iso) {
    const auto start = std::chrono::steady_clock::now();
    Surface s = setup_.surface(iso);
    if (s.update_ms <= 0)
      s.update_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return s;
  }

  void note_update(const Surface& s) {
    current_.mesh = s.mesh;
    current_.field = s.field;
    lines_surface_stale_ = true;
    vertices_ = s.mesh.vertex_count();
    triangles_ = s.mesh.triangle_count();
    last_ms_ = s.update_ms;
    detail_ = s.detail;
    message_.clear();
  }

  void retitle() {
    if (!setup_.title_for && !setup_.screen.title_for) return;
    try_options(scene_.options());
  }

  bool try_options(RenderOptions o) {
    o.title = title(iso_, o.color, screen_on_);
    try {
      scene_.set_options(o);
      return true;
    } catch (const Error& e) {
      message_ = e.what();
      return false;
    }
  }

  /// Shows `s`; when it lacks the array coloured now (an extra of an opened mesh, say) the colour
  /// goes back to H first, and the status line says so.
  std::string show_surface(const Surface& s) {
    RenderOptions o = scene_.options();
    const std::vector<std::string> q = field_quantities(s.field);
    if (!q.empty() && std::find(q.begin(), q.end(), canonical_quantity(o.color)) == q.end()) {
      const std::string was = o.color;
      o.color = std::find(q.begin(), q.end(), "H") != q.end() ? "H" : q.front();
      o.title = title(iso_, o.color, screen_on_);
      scene_.set_options(o);  // the old surface has H too (every estimate gives it)
      scene_.set_surface(s.mesh, s.field);
      return "colour " + was + " is not on this surface: showing " + o.color;
    }
    scene_.set_surface(s.mesh, s.field);
    return "";
  }

  /// Shows `s`, the volume's surface (`file` empty) or that mesh file's, and notes its update.
  void present(const Surface& s, const std::string& file) {
    const std::string note = show_surface(s);
    note_update(s);
    message_ = note;
    shown_ = file;
    mesh_stale_ = false;
  }

  /// A new screen-space image of the volume is shown: the mesh, if any, is of another isovalue
  /// or frame now.
  void note_cast() {
    shown_.clear();
    mesh_stale_ = true;
    message_.clear();
  }

  /// Re-extracts at `iso`; on failure keeps the previous surface and reports on the status line.
  void update(float iso) {
    if (screen_on_) return slide_screen(iso, false);  // re-cast, extract nothing
    if (iso == attempted_) return;  // the slider's release after a live update, or no move
    attempted_ = iso;
    try {
      present(call(iso), "");
      iso_ = iso;
      retitle();
    } catch (const Error& e) {
      message_ = "isovalue " + format(iso) + ": " + e.what();
    }
    refresh_status();
    window_->Render();
  }

  bool has_time() const { return setup_.frames >= 2 && setup_.set_frame; }

  /// Makes frame k current and re-extracts at the current isovalue; on failure keeps the frame
  /// shown and reports on the status line (and stops playing).
  void go_to_frame(int k) {
    k = std::max(0, std::min(setup_.frames - 1, k));
    if (k == frame_) return;
    try {
      setup_.set_frame(k);
      if (screen_on_) {
        if (!cast(iso_, false)) throw Error(message_);
        note_cast();
      } else {
        present(call(iso_), "");
      }
      frame_ = k;
      retitle();
    } catch (const Error& e) {
      message_ = "frame " + std::to_string(k) + ": " + e.what();
      playing_ = false;
      try {
        setup_.set_frame(frame_);  // back to the frame shown, so slider moves cut it again
      } catch (const Error&) {
      }
    }
    static_cast<vtkSliderRepresentation2D*>(time_slider_->GetRepresentation())->SetValue(frame_);
    refresh_status();
    window_->Render();
  }

  void make_time_slider() {
    vtkNew<vtkSliderRepresentation2D> rep;
    rep->SetMinimumValue(0);
    rep->SetMaximumValue(setup_.frames - 1);
    rep->SetValue(0);
    rep->SetTitleText("");
    rep->SetLabelFormat("%.0f");
    rep->GetPoint1Coordinate()->SetCoordinateSystemToNormalizedDisplay();
    rep->GetPoint2Coordinate()->SetCoordinateSystemToNormalizedDisplay();
    rep->SetSliderLength(0.02);
    rep->SetSliderWidth(0.03);
    rep->SetTubeWidth(0.008);
    rep->SetEndCapLength(0.01);
    rep->SetEndCapWidth(0.03);
    rep->SetLabelHeight(0.022);
    rep->GetTubeProperty()->SetColor(0.45, 0.6, 0.9);
    time_slider_->SetInteractor(interactor_);
    time_slider_->KeyPressActivationOff();
    time_slider_->SetRepresentation(rep);
    time_slider_->SetCurrentRenderer(scene_.overlay());
    time_slider_->SetDefaultRenderer(scene_.overlay());
    time_slider_->SetAnimationModeToJump();
    time_callback_->SetCallback(&Explorer::on_time_slider);
    time_callback_->SetClientData(this);
    time_slider_->AddObserver(vtkCommand::InteractionEvent, time_callback_);
    time_slider_->AddObserver(vtkCommand::EndInteractionEvent, time_callback_);
  }

  static void on_time_slider(vtkObject*, unsigned long event, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    if (event == vtkCommand::InteractionEvent && e->last_ms_ > kLiveUpdateMs) return;
    const double v = static_cast<vtkSliderRepresentation2D*>(e->time_slider_->GetRepresentation())->GetValue();
    e->go_to_frame(static_cast<int>(std::lround(v)));
  }

  static std::string format(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.5g", v);
    return text;
  }

  static std::string format_ms(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f ms", ms);
    return text;
  }

  void refresh_status() {
    const RenderOptions& o = scene_.options();
    std::string line = shown_.empty() ? "isovalue " + format(iso_) : "mesh " + shown_;
    if (screen_on_)
      line +=
          "   screen space: " + std::to_string(pixels_) + " of " + std::to_string(image_pixels_) +
          " pixels" +
          (cast_scale_ > 1 ? " (1/" + std::to_string(cast_scale_) + " resolution while dragging)"
                           : "");
    else
      line += "   " + std::to_string(vertices_) + " vertices, " + std::to_string(triangles_) +
              " triangles";
    line += "   update " + format_ms(last_ms_);
    if (!detail_.empty()) line += "   (" + detail_ + ")";
    std::string of;
    if (screen_on_) {
      of = " (H or K)";
    } else {
      const std::vector<std::string> arrays = field_quantities(current_.field);
      const auto at = std::find(arrays.begin(), arrays.end(), canonical_quantity(o.color));
      if (at != arrays.end())
        of = " (" + std::to_string(at - arrays.begin() + 1) + " of " +
             std::to_string(arrays.size()) + " arrays)";
    }
    line += "\n[c] colour: " + canonical_quantity(o.color) + of;
    if (!screen_on_)
      line += std::string("  [a] AO: ") + (uses_ao(o.shading) ? "on" : "off") +
              "  [d] directions: " + (o.dirs ? "on" : "off");
    line += "  [v] view: " + to_string(view_);
    if (setup_.screen.image)
      line += std::string("  [x] screen space: ") + (screen_on_ ? "on" : "off");
    line += "\n[r] reset view  [i] isovalue  [o] open  [w] save  [k] camera  [s] screenshot";
    if (setup_.lines && !screen_on_)
      line += std::string("  [l] lines: ") + (lines_on_ ? "on" : "off");
    if (has_time())
      line += "\nframe " + std::to_string(frame_) + " of " + std::to_string(setup_.frames) +
              (setup_.frame_label ? " (" + setup_.frame_label(frame_) + ")" : "") +
              (playing_ ? "   [space] pause" : "   [space] play");
    static const char* kPrompts[] = {"", "isovalue: ", "open mesh: ", "save surface as: "};
    if (entry_ != Entry::none)
      line += "\n" + std::string(kPrompts[static_cast<int>(entry_)]) + typed_ + "_   (Enter / Escape)";
    else if (!message_.empty())
      line += "\n" + message_;
    status_->SetInput(line.c_str());
  }

  void make_slider() {
    vtkNew<vtkSliderRepresentation2D> rep;
    rep->SetMinimumValue(setup_.min_value);
    rep->SetMaximumValue(setup_.max_value);
    rep->SetValue(setup_.isovalue);
    rep->SetTitleText("");  // the status line right below names the isovalue
    rep->SetLabelFormat("%.4g");
    rep->GetPoint1Coordinate()->SetCoordinateSystemToNormalizedDisplay();
    rep->GetPoint2Coordinate()->SetCoordinateSystemToNormalizedDisplay();  // placed by relayout
    rep->SetSliderLength(0.02);
    rep->SetSliderWidth(0.03);
    rep->SetTubeWidth(0.008);
    rep->SetEndCapLength(0.01);
    rep->SetEndCapWidth(0.03);
    rep->SetTitleHeight(0.025);
    rep->SetLabelHeight(0.022);
    slider_->SetInteractor(interactor_);
    slider_->KeyPressActivationOff();  // 'i' is ours (typing an isovalue), not the widget's toggle
    slider_->SetRepresentation(rep);
    slider_->SetCurrentRenderer(scene_.overlay());
    slider_->SetDefaultRenderer(scene_.overlay());
    slider_->SetAnimationModeToJump();
    slider_callback_->SetCallback(&Explorer::on_slider);
    slider_callback_->SetClientData(this);
    slider_->AddObserver(vtkCommand::InteractionEvent, slider_callback_);
    slider_->AddObserver(vtkCommand::EndInteractionEvent, slider_callback_);
  }

  float slider_value() const {
    return static_cast<float>(static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation())->GetValue());
  }

  static void on_slider(vtkObject*, unsigned long event, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    if (e->screen_on_)
      return e->slide_screen(e->slider_value(), event == vtkCommand::InteractionEvent);
    if (event == vtkCommand::InteractionEvent && e->last_ms_ > kLiveUpdateMs) return;  // wait for release
    e->update(e->slider_value());
  }

  static void on_timer(vtkObject*, unsigned long, void* self, void* data) {
    auto* e = static_cast<Explorer*>(self);
    const int id = data ? *static_cast<int*>(data) : -1;
    if (id == e->play_timer_) {
      if (e->playing_ && e->entry_ == Entry::none) e->go_to_frame((e->frame_ + 1) % e->setup_.frames);
      return;
    }
    if (id == e->script_timer_) e->step();
  }

  /// Before each frame: new lines when they are on and the camera or the surface changed.
  static void on_render_start(vtkObject*, unsigned long, void* self, void*) {
    auto* e = static_cast<Explorer*>(self);
    vtkCamera* cam = e->scene_.renderer()->GetActiveCamera();
    if (!e->lines_on_ || e->screen_on_ ||
        (!e->lines_surface_stale_ && cam->GetMTime() == e->lines_camera_time_))
      return;
    try {
      e->overlay_.set_lines(e->setup_.lines(e->current_, camera_of(cam), e->lines_surface_stale_));
    } catch (const Error& err) {
      e->message_ = std::string("lines: ") + err.what();
      e->lines_on_ = false;
      e->overlay_.set_visible(false);
      e->refresh_status();
    }
    e->lines_surface_stale_ = false;
    e->lines_camera_time_ = cam->GetMTime();
  }

  void step() {
    if (next_action_ >= setup_.script.size()) {
      interactor_->TerminateApp();
      return;
    }
    const ExplorerAction& a = setup_.script[next_action_++];
    switch (a.kind) {
      case ExplorerAction::Kind::SetIsovalue:
        // as a user would: move the slider, then release it
        static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation())->SetValue(a.isovalue);
        slider_->InvokeEvent(vtkCommand::InteractionEvent);
        slider_->InvokeEvent(vtkCommand::EndInteractionEvent);
        break;
      case ExplorerAction::Kind::Key:
        interactor_->SetKeyEventInformation(0, 0, a.key, 1, std::string(1, a.key).c_str());
        interactor_->CharEvent();
        break;
      case ExplorerAction::Kind::Type:
        for (char c : a.path) {
          interactor_->SetKeyEventInformation(0, 0, c, 1, std::string(1, c).c_str());
          interactor_->CharEvent();
        }
        break;
      case ExplorerAction::Kind::Resize:
        window_->SetSize(a.width, a.height);
        relayout(a.width, a.height);
        window_->Render();
        break;
      case ExplorerAction::Kind::Screenshot:
        screenshot(a.path);
        break;
      case ExplorerAction::Kind::SetFrame:
        if (!has_time()) break;
        static_cast<vtkSliderRepresentation2D*>(time_slider_->GetRepresentation())->SetValue(a.frame);
        time_slider_->InvokeEvent(vtkCommand::InteractionEvent);
        time_slider_->InvokeEvent(vtkCommand::EndInteractionEvent);
        break;
    }
  }

  std::string next_screenshot_name() {
    for (;;) {
      char suffix[24];
      std::snprintf(suffix, sizeof suffix, "-%03d.png", ++screenshots_);
      const std::string name = setup_.screenshot_prefix + suffix;
      if (!std::filesystem::exists(name)) return name;
    }
  }

  void screenshot(const std::string& path) {
    try {
      save_png(window_, path);
      message_ = "saved " + path;
      std::cout << "saved screenshot: " << path << std::endl;
    } catch (const Error& e) {
      message_ = e.what();
      std::cerr << e.what() << std::endl;
    }
  }

  const ExplorerSetup& setup_;
  CurvatureScene scene_;
  vtkNew<vtkRenderWindow> window_;
  vtkNew<vtkRenderWindowInteractor> interactor_;
  vtkNew<ExplorerStyle> style_;
  vtkNew<vtkSliderWidget> slider_;
  vtkNew<vtkSliderWidget> time_slider_;  // frames of a time series (setup.frames >= 2)
  vtkNew<vtkCallbackCommand> time_callback_;
  int frame_ = 0;           // frame shown
  bool playing_ = false;    // space
  int play_timer_ = -1, script_timer_ = -1;
  vtkNew<vtkTextActor> status_;
  vtkNew<vtkCallbackCommand> slider_callback_;
  vtkNew<vtkCallbackCommand> timer_callback_;
  vtkNew<vtkCallbackCommand> resize_callback_;
  Surface current_;            // the surface shown (for 'w' and the lines)
  std::string shown_;          // the mesh file shown, empty for the volume's isosurface
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
  bool lines_surface_stale_ = true;      // the surface changed since the lines were made
  vtkMTimeType lines_camera_time_ = 0;   // the camera's MTime when they were made
  float iso_ = 0;        // isovalue of the surface shown
  float attempted_ = 0;  // last isovalue the callback was asked for
  std::size_t vertices_ = 0, triangles_ = 0;
  double last_ms_ = 0;
  std::string detail_, message_;
  std::size_t next_action_ = 0;
  int screenshots_ = 0;
};

void ExplorerStyle::OnChar() {
  const char key = this->Interactor ? this->Interactor->GetKeyCode() : 0;
  if (explorer && explorer->on_key(key)) return;
  vtkInteractorStyleTrackballCamera::OnChar();  // r, q/e, w, f, ...
}

}  // namespace

void run_explorer(const ExplorerSetup& setup) {
  if (!setup.surface) throw Error("explorer: no surface callback given");
  if (!(setup.min_value < setup.max_value))
    throw Error("explorer: empty isovalue range [" + std::to_string(setup.min_value) + ", " +
                std::to_string(setup.max_value) + "]");
  if (setup.isovalue < setup.min_value || setup.isovalue > setup.max_value)
    throw Error("explorer: isovalue " + std::to_string(setup.isovalue) + " outside the value range [" +
                std::to_string(setup.min_value) + ", " + std::to_string(setup.max_value) + "]");
  if (setup.view.width < 64 || setup.view.height < 64) throw Error("explorer: window too small");
  canonical_quantity(setup.view.color);
  const char* display = std::getenv("DISPLAY");
  if (setup.script.empty() && !(display && *display))
    throw Error("no X display (DISPLAY is unset): the interactive explorer needs one; render PNGs headless instead");
  ensure_display(setup.script.empty() ? DisplayUse::interactive : DisplayUse::offscreen);
  Explorer explorer(setup);
  explorer.run();
}

}  // namespace isocurv::viz
