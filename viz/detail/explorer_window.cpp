// The explorer's window: opening it, laying out the surface, legend, sliders and status line,
// following resizes, and the timer that plays a series and runs a script.
#include "viz/detail/explorer.h"

#include <algorithm>

#include <vtkCommand.h>
#include <vtkRenderer.h>
#include <vtkSliderRepresentation2D.h>
#include <vtkTextProperty.h>

#include "viz/headless_display.h"

namespace isocurv::viz::detail {

void Explorer::run() {
  // A mesh series has no volume to cast before the first mesh: it starts on that mesh, then
  // switches to screen space below.
  const bool start_screen = setup_.screen.start_on && setup_.screen.image && setup_.has_isovalue;
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
    scene_.set_options(ranged(first_options, true));
    scene_.set_surface(first.mesh, first.field);
    note_update(first);
    hold_first_frame_ranges();
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
  if (setup_.has_isovalue) make_slider();
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
  if (setup_.screen.start_on && setup_.screen.image && !start_screen) enter_screen();
  refresh_status();
  resize_callback_->SetCallback(&Explorer::on_resize);
  resize_callback_->SetClientData(this);
  window_->AddObserver(vtkCommand::WindowResizeEvent, resize_callback_);

  interactor_->Initialize();
  if (setup_.has_isovalue) slider_->EnabledOn();
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
  if (setup_.has_isovalue) slider_->EnabledOff();
  if (has_time()) time_slider_->EnabledOff();
  window_->Finalize();
}

void Explorer::relayout(int width, int height) {
  const int font = std::max(11, static_cast<int>(height * kStatusFontPerPixel));
  status_->GetTextProperty()->SetFontSize(font);
  const int status_px = static_cast<int>((kStatusLines + (has_time() ? 1 : 0)) * font * 1.25);
  const int slider_px = std::max(static_cast<int>(kSliderBand * height), 2 * font);
  const int bands = (setup_.has_isovalue ? 1 : 0) + (has_time() ? 1 : 0);  // a slider each
  scene_.set_size(width, height);
  scene_.set_bottom_reserved(status_px + slider_px * bands);
  const double right = scene_.layout().surface.x1 / double(width);
  if (setup_.has_isovalue) {
    auto* rep = static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation());
    const double y = (status_px + 0.5 * slider_px) / double(height);
    rep->GetPoint1Coordinate()->SetValue(0.08, y);
    rep->GetPoint2Coordinate()->SetValue(std::max(0.3, right - 0.08), y);
  }
  if (has_time()) {  // the time slider in a band of its own above the isovalue's (if any)
    auto* t = static_cast<vtkSliderRepresentation2D*>(time_slider_->GetRepresentation());
    const double yt = (status_px + (bands - 0.5) * slider_px) / double(height);
    t->GetPoint1Coordinate()->SetValue(0.08, yt);
    t->GetPoint2Coordinate()->SetValue(std::max(0.3, right - 0.08), yt);
  }
}

void Explorer::on_resize(vtkObject*, unsigned long, void* self, void*) {
  auto* e = static_cast<Explorer*>(self);
  const int* size = e->window_->GetSize();
  if (size[0] < 16 || size[1] < 16) return;
  if (size[0] == e->scene_.options().width && size[1] == e->scene_.options().height) return;
  e->relayout(size[0], size[1]);
}

void Explorer::on_timer(vtkObject*, unsigned long, void* self, void* data) {
  auto* e = static_cast<Explorer*>(self);
  const int id = data ? *static_cast<int*>(data) : -1;
  if (id == e->play_timer_)
    e->play_tick();
  else if (id == e->script_timer_)
    e->step();
}

}  // namespace isocurv::viz::detail
