// Colour ranges held across the frames of a series (ExplorerSetup::shared_color_range), so that
// an animation does not flicker: each array keeps the range the first frame gave it.
#include "viz/detail/explorer.h"

#include <string>
#include <vector>

#include "core/error.h"
#include "viz/quantity.h"

namespace isocurv::viz::detail {

bool Explorer::holds_ranges(bool frame) const {
  return setup_.shared_color_range && !setup_.view.range && !screen_on_ && frame;
}

RenderOptions Explorer::ranged(RenderOptions o, bool frame) const {
  o.range = setup_.view.range;
  if (!holds_ranges(frame)) return o;
  const auto held = held_ranges_.find(canonical_quantity(o.color));
  if (held != held_ranges_.end()) o.range = held->second;
  return o;
}

void Explorer::hold_range(bool frame) {
  if (!holds_ranges(frame)) return;
  const std::string q = canonical_quantity(scene_.options().color);
  if (held_ranges_.count(q) == 0) held_ranges_[q] = ColorRange{scene_.range_lo(), scene_.range_hi()};
}

void Explorer::hold_first_frame_ranges() {
  if (!holds_ranges(true)) return;
  const RenderOptions shown = scene_.options();
  for (const std::string& q : field_quantities(current_.field)) {
    if (held_ranges_.count(q)) continue;
    RenderOptions o = shown;
    o.color = q;
    o.range.reset();
    try {
      scene_.set_options(o);  // the range the scene gives this array on this frame alone
      held_ranges_[q] = ColorRange{scene_.range_lo(), scene_.range_hi()};
    } catch (const Error&) {
      // an array the scene cannot colour: it is held when (if ever) it is shown
    }
  }
  scene_.set_options(ranged(shown, true));
}

}  // namespace isocurv::viz::detail
