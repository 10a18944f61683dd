#pragma once
// The screen stage's outputs: the picture (PNG, with title and colour-bar legend laid out as
// isocurv render does) and the raw per-pixel values (.vti).
// Tested through the screen command: tests/app/test_screen_cli.cpp.
#include <string>

#include "screen/estimate.h"
#include "screen/gbuffer.h"
#include "viz/color_map.h"
#include "viz/picture_layout.h"
#include "viz/screen_image.h"

namespace isocurv::screen {

/// What the picture shows.
struct PictureOptions {
  std::string quantity = "H";            ///< "H" or "K"
  std::string cmap = "auto";             ///< viz::color_map_names
  std::optional<viz::ColorRange> range;  ///< fixed colour range; else viz::color_range's
  double clamp_percentile = 2;
  std::string title;        ///< none when empty
  std::string length_unit;  ///< the legend's unit ("mm"); empty: "length"
  bool shade = true;  ///< colours times (0.15 + 0.85 |n . view|): render's Lambert headlight
};

/// The layout of a width x height picture whose colour range is `range` (viz::layout_picture):
/// its `surface` box is where, and how large, the screen-space image goes. `no_data`: the legend
/// has the "no data" swatch (surface pixels without an estimate, has_unestimated).
viz::PictureLayout screen_layout(int width, int height, const PictureOptions& options,
                                 const viz::ColorRange& range, bool no_data = false);

/// True when some pixel sees the surface (g.valid) but has no estimate (c.valid 0: a depth
/// discontinuity, a pixel whose stencil leaves the surface): write_picture draws those in the
/// map's "no data" colour.
bool has_unestimated(const GBuffer& g, const ScreenCurvature& c);

/// The colour range of `c`'s valid values of options.quantity (viz::color_range); an image
/// without valid pixels gets options.range or [-1, 1].
viz::ColorRange screen_range(const ScreenCurvature& c, const PictureOptions& options);

/// Writes the picture atomically: the background, title and legend of `layout` (rendered by VTK
/// offscreen; a private Xvfb when there is no display), then `c`'s valid pixels coloured (and
/// shaded by `g`'s normals) pasted into layout.surface, whose size must be c's. Surface pixels
/// without an estimate take the map's "no data" colour (viz::no_data_color, shaded; the layout's
/// swatch names it); pixels off the surface show the background. @throw Error naming `path` for a failed render or write, or a size
/// mismatch
void write_picture(const std::string& path, const GBuffer& g, const ScreenCurvature& c,
                   const viz::PictureLayout& layout, const PictureOptions& options,
                   const viz::ColorRange& range);

/// `c` (moved from) as the explorer's screen-space image: H, valid, the view shading of `g`
/// (view_shading), and K unless the estimator gives none (Mellado: `with_k` false).
viz::ScreenImage explorer_image(const GBuffer& g, ScreenCurvature&& c, bool with_k);

/// Writes `c` as VTK image data (.vti, vtkXMLImageDataWriter, atomically), float point arrays
/// `H`, `K` (0 where invalid) and `Valid` (1 or 0), spacing 1, origin 0, y up. Without `layout`,
/// c.width x c.height points (pixel (x, y) is point x + width y); with it, the picture's grid:
/// layout->width x layout->height points, c placed in layout->surface, so that point (x, y) is
/// the PNG's pixel (x, y) counted from its bottom-left corner (Valid 0 outside the surface box).
/// @throw Error naming `path` on failure
void write_raw(const std::string& path, const ScreenCurvature& c,
               const viz::PictureLayout* layout = nullptr);

}  // namespace isocurv::screen
