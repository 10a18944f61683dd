// Scripted runs (ExplorerSetup::script): one action per timer tick, each done as a user would.
#include "viz/detail/explorer.h"

#include <vtkCommand.h>
#include <vtkSliderRepresentation2D.h>

namespace isocurv::viz::detail {

void Explorer::step() {
  if (next_action_ >= setup_.script.size()) {
    interactor_->TerminateApp();
    return;
  }
  const ExplorerAction& a = setup_.script[next_action_++];
  switch (a.kind) {
    case ExplorerAction::Kind::SetIsovalue:
      if (!setup_.has_isovalue) break;  // no slider
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
    case ExplorerAction::Kind::Status:
      write_status(a.path);
      break;
    case ExplorerAction::Kind::Wait:
      break;
  }
}

}  // namespace isocurv::viz::detail
