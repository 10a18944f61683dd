#pragma once
// Where the title, the legend (colour bar, its title and labels) and the surface go in a picture,
// with text measured by VTK's FreeType renderer so that nothing is clipped from 300x300 to 4k.
// Tested in tests/viz/test_picture_layout.cpp, tests/viz/test_color_map.cpp.
#include <string>
#include <vector>

namespace isocurv::viz {

/// A rectangle of pixels, [x0, x1) x [y0, y1), y up from the image's bottom row (VTK display
/// coordinates). Empty when x1 <= x0 or y1 <= y0.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  /// True when `b` lies inside this box (an empty `b` always does).
  bool contains(const PixelBox& b) const {
    return b.empty() || (b.x0 >= x0 && b.y0 >= y0 && b.x1 <= x1 && b.y1 <= y1);
  }
  bool overlaps(const PixelBox& b) const {
    return !empty() && !b.empty() && b.x0 < x1 && x0 < b.x1 && b.y0 < y1 && y0 < b.y1;
  }
};

/// One line or block of text placed in the picture: draw it left- and bottom-justified with its
/// anchor at (x, y); `box` is the ink it covers (measured).
struct PlacedText {
  std::string text;
  int font_px = 12;
  int x = 0, y = 0;
  PixelBox box;
};

/// The picture's parts for an image of width x height pixels.
struct PictureLayout {
  int width = 0, height = 0;
  PixelBox surface;         ///< the free part the surface is framed in (viewport of its renderer)
  PlacedText title;         ///< empty text when there is no title; shortened to fit the width
  PlacedText legend_title;  ///< quantity and unit, one or two lines, above the bar
  PixelBox bar;             ///< the colour bar, lo at the bottom, hi at the top
  std::vector<PlacedText> labels;  ///< one per tick, beside the bar
  std::vector<double> ticks;       ///< the tick values, bottom to top
  PixelBox no_data;                ///< the "no data" swatch under the bar (empty when not asked for)
  PlacedText no_data_label;        ///< "no data", beside the swatch
  PixelBox legend;                 ///< everything of the legend (title, bar, labels, swatch)
  /// Label maps (layout_picture's `categories`): instead of the bar and its ticks, one swatch
  /// per label shown, top to bottom in ascending order, its value in `labels` beside it;
  /// swatch_category[i] is swatches[i]'s index among the categories (its colour,
  /// viz::categorical_color). When not all fit, a last line in `labels` says how many more.
  std::vector<PixelBox> swatches;
  std::vector<std::size_t> swatch_category;
};

/// The ink extents of `text` (UTF-8, lines split at '\n') at `font_px` (Arial, as drawn by
/// vtkTextActor at 72 dpi), relative to its left-bottom anchor: [bbox[0], bbox[1]] x [bbox[2],
/// bbox[3]]. Returns {0, 0, 0, 0} for an empty text.
PixelBox measure_text(const std::string& text, int font_px);

/// Lays out a picture: the title centred at the top (its font shrunk, then the text shortened
/// from the left with "...", until it fits the width), the legend in a column on the right
/// (`legend_title`, then a bar with labels for 5 ticks from lo to hi), and the surface in the
/// rest, above `bottom_reserved` pixels (the explorer's status line and slider). Font sizes grow
/// with the image (about min(width, height) / 36 pixels, 9 to 48) and shrink where the legend
/// would take more than 40% of the width. With `no_data`, a swatch labelled "no data" sits under
/// the bar (the colour of the vertices that were not measured). Every text box lies inside the
/// image. With `categories` (a label map's values, ascending), the legend lists them as
/// swatches (PictureLayout::swatches) instead of the bar; lo and hi are then not used.
PictureLayout layout_picture(int width, int height, const std::string& title,
                             const std::string& legend_title, double lo, double hi,
                             int bottom_reserved = 0, bool no_data = false,
                             const std::vector<double>* categories = nullptr);

/// A value whose tick label (tick_label: %.3g, "-8.88e+88") is as wide as any: a legend laid out
/// for it does not narrow when the values change.
inline constexpr double kWidestLegendValue = 8.88e88;

/// The right edge of the surface's box that does not depend on what is coloured: the narrowest
/// of layout_picture's boxes for the widest values (+-kWidestLegendValue) under `legend_title` and
/// under a reference two-line title. Render, the explorer and `screen` clip their surface box to
/// it, so that switching the coloured array (or the values) never moves the camera.
int stable_surface_right(int width, int height, const std::string& title,
                         const std::string& legend_title, int bottom_reserved = 0);

/// A label value as the legend writes it (%g, up to 10 significant digits: labels are integers).
std::string category_label(double value);

/// A tick label for a legend spanning `range` (hi - lo): %g with at least 3 significant digits,
/// more when the range is small beside the value, so that the 5 ticks of a near-constant array
/// still read apart; values within 1e-9 of the range of zero are shown as 0.
std::string tick_label(double value, double range);

}  // namespace isocurv::viz
