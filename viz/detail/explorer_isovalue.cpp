// The isovalue slider: live re-extraction while updates are fast, on release otherwise.
#include "viz/detail/explorer.h"

#include <vtkCommand.h>
#include <vtkSliderRepresentation2D.h>

#include "core/error.h"

namespace isocurv::viz::detail {

void Explorer::make_slider() {
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

float Explorer::slider_value() const {
  return static_cast<float>(static_cast<vtkSliderRepresentation2D*>(slider_->GetRepresentation())->GetValue());
}

void Explorer::on_slider(vtkObject*, unsigned long event, void* self, void*) {
  auto* e = static_cast<Explorer*>(self);
  if (e->screen_on_)
    return e->slide_screen(e->slider_value(), event == vtkCommand::InteractionEvent);
  if (event == vtkCommand::InteractionEvent && e->last_ms_ > kLiveUpdateMs) return;  // wait for release
  e->update(e->slider_value());
}

void Explorer::update(float iso) {
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

}  // namespace isocurv::viz::detail
