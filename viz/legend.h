#pragma once
// The picture's 2D overlay: title, colour bar with its title and tick labels, drawn where a
// PictureLayout puts them.
// Tested in tests/viz/test_explorer_screen.cpp and the pictures of tests/viz/test_render.cpp.
#include <memory>

#include "viz/color_map.h"
#include "viz/picture_layout.h"

class vtkRenderer;

namespace isocurv::viz {

/// VTK actors for a PictureLayout's texts and colour bar, added to one renderer (the scene's
/// full-window background renderer). Not thread-safe; lives as long as its owner's renderer.
class Legend {
 public:
  explicit Legend(vtkRenderer* renderer);
  ~Legend();
  Legend(const Legend&) = delete;
  Legend& operator=(const Legend&) = delete;

  /// Places the texts and the bar as `layout` says; the bar shows `cmap` (resolved) over `range`,
  /// lo at the bottom, and the layout's "no data" swatch (when it has one) no_data_color(cmap).
  /// `show_bar` false hides the bar, its title, labels and swatch (not the title).
  void update(const PictureLayout& layout, const std::string& cmap, const ColorRange& range,
              bool show_bar = true);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace isocurv::viz
