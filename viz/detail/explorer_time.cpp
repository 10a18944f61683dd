// The time slider of a series and its frames (play / pause is the space key and the play
// timer).
#include "viz/detail/explorer.h"

#include <algorithm>
#include <cmath>

#include <vtkCommand.h>
#include <vtkProperty2D.h>
#include <vtkSliderRepresentation2D.h>

#include "core/error.h"

namespace isocurv::viz::detail {

bool Explorer::has_time() const { return setup_.frames >= 2 && setup_.set_frame; }

void Explorer::play_tick() {
  if (playing_ && entry_ == Entry::none) go_to_frame((frame_ + 1) % setup_.frames);
}

void Explorer::go_to_frame(int k) {
  k = std::max(0, std::min(setup_.frames - 1, k));
  if (k == frame_) return;
  try {
    setup_.set_frame(k);
    if (screen_on_ && setup_.has_isovalue) {
      if (!cast(iso_, false)) throw Error(message_);
      note_cast();
    } else {
      present(call(iso_), "");  // a mesh series in screen-space mode: rasterised before drawing
      image_stale_ = true;
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

void Explorer::make_time_slider() {
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

void Explorer::on_time_slider(vtkObject*, unsigned long event, void* self, void*) {
  auto* e = static_cast<Explorer*>(self);
  if (event == vtkCommand::InteractionEvent && e->last_ms_ > kLiveUpdateMs) return;
  const double v = static_cast<vtkSliderRepresentation2D*>(e->time_slider_->GetRepresentation())->GetValue();
  e->go_to_frame(static_cast<int>(std::lround(v)));
}

}  // namespace isocurv::viz::detail
