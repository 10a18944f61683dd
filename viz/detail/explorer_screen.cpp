// Screen-space mode ('x'): curvature per pixel cast by the setup's callback, re-cast when the
// isovalue, the camera or the window changes, coarser while the mouse drags.
#include "viz/detail/explorer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <vtkCommand.h>

#include "core/error.h"
#include "viz/quantity.h"

namespace isocurv::viz::detail {

std::string Explorer::screen_quantity(const std::string& color) {
  const std::string q = canonical_quantity(color);
  return q == "H" || q == "K" ? q : "H";
}

void Explorer::enter_screen() {
  RenderOptions o = scene_.options();
  o.color = screen_quantity(o.color);
  o.title = title(iso_, o.color, true);
  o.range = setup_.view.range;  // an image's own range, not one held for the frames' meshes
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

void Explorer::leave_screen() {
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
  try_options(scene_.options());  // the title, and the range a frame holds
}

bool Explorer::same_camera(const Camera& a, const Camera& b) {
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

bool Explorer::cast(float iso, bool of_mesh, int scale) {
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

void Explorer::on_overlay_start(vtkObject*, unsigned long, void* self, void*) {
  auto* e = static_cast<Explorer*>(self);
  if (!e->screen_on_) return;
  const PixelBox& box = e->scene_.layout().surface;
  const int scale = e->interacting_ || e->sliding_ ? e->coarse_scale() : 1;
  if (!e->image_stale_ && same_camera(e->scene_.current_camera(), e->cast_camera_) &&
      box.x1 - box.x0 == e->cast_w_ && box.y1 - box.y0 == e->cast_h_ && scale == e->cast_scale_)
    return;
  e->cast(e->iso_, e->shows_mesh(), scale);
  e->refresh_status();
}

int Explorer::coarse_scale() const {
  return full_ms_ <= kLiveUpdateMs ? 1 : full_ms_ <= 4 * kLiveUpdateMs ? 2 : 4;
}

void Explorer::slide_screen(float iso, bool live) {
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

void Explorer::on_interaction(vtkObject*, unsigned long event, void* self, void*) {
  auto* e = static_cast<Explorer*>(self);
  e->interacting_ = event == vtkCommand::StartInteractionEvent;
  if (!e->interacting_ && e->screen_on_ && e->cast_scale_ > 1)
    e->window_->Render();  // full image
}

void Explorer::note_cast() {
  shown_.clear();
  mesh_stale_ = true;
  message_.clear();
}

}  // namespace isocurv::viz::detail
