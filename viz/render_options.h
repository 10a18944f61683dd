#pragma once
// How a curvature surface is shown: shared by render_png and the explorer.
// Tested in tests/viz/test_render.cpp, tests/viz/test_explorer_screen.cpp (through its users).
#include <optional>
#include <array>
#include <string>
#include <vector>

#include "core/camera.h"
#include "viz/color_map.h"

namespace isocurv::viz {

/// How the surface is lit (--shading). VTK's headlight gives ambient + diffuse (Lambert) +
/// a little specular; AO is the per-vertex ambient-occlusion array (1 open, 0 fully occluded).
enum class Shading {
  lambert,     ///< ambient + diffuse, no AO
  ambient_ao,  ///< the ambient term times AO, diffuse kept (Griffin et al. 2012, section 3.7)
  both,        ///< the ambient and the diffuse term times AO (the colour itself darkened)
};

/// Parses "lambert", "ambient-ao", "both". @throw Error naming the choices.
Shading parse_shading(const std::string& name);
/// The name parse_shading accepts.
std::string to_string(Shading s);
/// True when `s` needs the AO array.
inline bool uses_ao(Shading s) { return s != Shading::lambert; }

/// What to show and how.
struct RenderOptions {
  std::string color = "H";    ///< colour quantity: H, K, k1, k2, ShapeIndex, Curvedness or AO
  std::string cmap = "auto";  ///< colour map (color_map_names; auto: by quantity)
  std::optional<ColorRange>
      range;                    ///< --range MIN MAX: exactly this range instead of color_range's
  double clamp_percentile = 2;  ///< --percentile: outliers ignored by color_range (each end)
  Shading shading = Shading::lambert;
  bool dirs = false;       ///< draw principal-direction glyphs (direction_glyphs)
  int dirs_count = 0;      ///< about this many glyph sites over the surface; 0: from the image size
  double dirs_length = 0;  ///< glyph length in world units; 0: 0.7 x their spacing
  int width = 1024, height = 768;  ///< image (or window) size in pixels
  std::string title;               ///< text at the top of the image; none when empty
  std::string length_unit;  ///< the volume's length unit for the legend ("mm"); empty: "length"
  ViewSpec view;            ///< viewpoint, turns, zoom and projection (fit_camera)
  std::optional<Camera> camera;  ///< when set, used as it is instead of fitting `view`
  /// When not empty (and no `camera`), the camera is fitted to these points (world units)
  /// instead of the mesh's framing points: the pictures of a sweep or series share a camera.
  std::vector<std::array<double, 3>> frame_points;
};

}  // namespace isocurv::viz
