// The surface shown: asking the setup's callback for one, showing it (falling back to H when it
// lacks the colour), the title and the render options.
#include "viz/detail/explorer.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/error.h"
#include "viz/quantity.h"

namespace isocurv::viz::detail {

std::string Explorer::title(float iso, const std::string& quantity, bool screen) const {
  if (screen && setup_.screen.title_for) return setup_.screen.title_for(iso, quantity);
  if (setup_.title_for) return setup_.title_for(iso, quantity);
  return setup_.view.title;
}

Surface Explorer::call(float iso) {
  const auto start = std::chrono::steady_clock::now();
  Surface s = setup_.surface(iso);
  if (s.update_ms <= 0)
    s.update_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return s;
}

void Explorer::note_update(const Surface& s) {
  current_.mesh = s.mesh;
  current_.field = s.field;
  lines_surface_stale_ = true;
  vertices_ = s.mesh.vertex_count();
  triangles_ = s.mesh.triangle_count();
  last_ms_ = s.update_ms;
  detail_ = s.detail;
  message_.clear();
}

void Explorer::retitle() {
  if (!setup_.title_for && !setup_.screen.title_for) return;
  try_options(scene_.options());
}

bool Explorer::try_options(RenderOptions o) {
  o.title = title(iso_, o.color, screen_on_);
  o = ranged(std::move(o), shown_.empty());
  try {
    scene_.set_options(o);
    hold_range(shown_.empty());
    return true;
  } catch (const Error& e) {
    message_ = e.what();
    return false;
  }
}

std::string Explorer::show_surface(const Surface& s, bool frame) {
  RenderOptions o = scene_.options();
  const std::vector<std::string> q = field_quantities(s.field);
  std::string note;
  if (!q.empty() && std::find(q.begin(), q.end(), canonical_quantity(o.color)) == q.end()) {
    const std::string was = o.color;
    o.color = std::find(q.begin(), q.end(), "H") != q.end() ? "H" : q.front();
    o.title = title(iso_, o.color, screen_on_);
    note = "colour " + was + " is not on this surface: showing " + o.color;
  }
  o = ranged(std::move(o), frame);
  const RenderOptions& now = scene_.options();
  const bool same_range = o.range.has_value() == now.range.has_value() &&
                          (!o.range || (o.range->lo == now.range->lo && o.range->hi == now.range->hi));
  if (!note.empty() || !same_range)
    scene_.set_options(o);  // the old surface has H too (every estimate gives it)
  scene_.set_surface(s.mesh, s.field);
  hold_range(frame);
  return note;
}

void Explorer::present(const Surface& s, const std::string& file) {
  const std::string note = show_surface(s, file.empty());
  note_update(s);
  message_ = note;
  shown_ = file;
  mesh_stale_ = false;
}

}  // namespace isocurv::viz::detail
