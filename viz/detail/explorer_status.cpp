// The status line under the sliders: what is shown, the timings, the keys' states, the frame,
// and what is being typed or the last message.
#include "viz/detail/explorer.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

#include "viz/quantity.h"

namespace isocurv::viz::detail {

std::string Explorer::format(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.5g", v);
  return text;
}

std::string Explorer::format_ms(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f ms", ms);
  return text;
}

void Explorer::refresh_status() {
  const RenderOptions& o = scene_.options();
  std::string line = !shown_.empty()        ? "mesh " + shown_
                     : setup_.has_isovalue ? "isovalue " + format(iso_)
                                           : "mesh of frame " + std::to_string(frame_);
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
  line += std::string("\n[r] reset view") + (setup_.has_isovalue ? "  [i] isovalue" : "") +
          "  [o] open  [w] save  [k] camera  [s] screenshot";
  if (setup_.lines && !screen_on_)
    line += std::string("  [l] lines: ") + (lines_on_ ? "on" : "off");
  line += "  [q] quit";
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

void Explorer::write_status(const std::string& path) {
  std::ofstream out(path);
  const char* text = status_->GetInput();
  out << (text ? text : "") << '\n';
  if (!out) {
    message_ = "cannot write the status line to " + path;
    std::cerr << message_ << std::endl;
  }
}

}  // namespace isocurv::viz::detail
