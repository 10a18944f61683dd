// The feature-line overlay ('l'): recomputed before a frame when the camera or the surface moved.
#include "viz/detail/explorer.h"

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "core/error.h"

namespace isocurv::viz::detail {

void Explorer::on_render_start(vtkObject*, unsigned long, void* self, void*) {
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

}  // namespace isocurv::viz::detail
