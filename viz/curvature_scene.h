#pragma once
// A VTK scene showing one curvature surface: the coloured, shaded mesh, optional direction
// glyphs, and a 2D overlay with the title and the legend laid out so that neither covers the
// surface (picture_layout.h). Used by render_png and the explorer.
// Tested in tests/viz/test_explorer_screen.cpp, tests/viz/test_render.cpp.
#include <memory>

#include "core/camera.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "viz/picture_layout.h"
#include "viz/render_options.h"
#include "viz/screen_image.h"

class vtkPolyData;
class vtkRenderWindow;
class vtkRenderer;

namespace isocurv::viz {

/// The background: a vertical gradient from kBackgroundBottom to kBackgroundTop (RGB, 0..1).
constexpr double kBackgroundBottom[3] = {0.08, 0.08, 0.10};
constexpr double kBackgroundTop[3] = {0.30, 0.31, 0.36};

class CurvatureScene {
 public:
  CurvatureScene();
  ~CurvatureScene();
  CurvatureScene(const CurvatureScene&) = delete;
  CurvatureScene& operator=(const CurvatureScene&) = delete;

  /// The 3D renderer (owned by the scene): the surface and glyphs, in the viewport
  /// layout().surface; add 3D overlays here. It draws on layer 1, over overlay().
  vtkRenderer* renderer() const;
  /// The full-window 2D renderer on layer 0 (owned): background, title, legend; the explorer's
  /// status line and slider go here.
  vtkRenderer* overlay() const;
  /// Gives `window` two layers and adds both renderers to it. Call once per window.
  void attach(vtkRenderWindow* window);

  /// Shows `mesh` with `field` (copied), recoloured with the current options. An empty mesh shows
  /// nothing. Throws Error when the field's arrays do not match the vertex count, or (for a
  /// non-empty mesh) when it lacks the current colour quantity or, with AO shading, the AO array.
  void set_surface(const Mesh& mesh, const curvature::CurvatureField& field);

  /// Screen-space mode (the explorer's 'x'). While on, the mesh and its glyphs are hidden and the
  /// image of set_image fills layout().surface instead, coloured by options().color (then "H" or
  /// "K"), with the legend over the image's valid values. The surface box is then laid out for
  /// the widest legend labels, so it depends on the window size alone and an image cast at its
  /// size keeps fitting whatever its values. Turning it on with another colour throws Error.
  void set_image_mode(bool on);
  bool image_mode() const;
  /// The image shown in screen-space mode (copied): each pixel a `scale` x `scale` block from
  /// layout().surface's bottom-left corner, cut at the box (a coarser image while the camera is
  /// dragged). @throw Error for arrays that do not match its size, scale < 1, or colour K with an
  /// image that has no K; the previous image then stays.
  void set_image(const ScreenImage& image, int scale = 1);

  /// Applies every option but the camera's (frame_camera does that). Throws Error as
  /// set_surface does, and for an unknown map or an empty --range; the previous options stay.
  void set_options(const RenderOptions& options);
  const RenderOptions& options() const;

  /// The window's size changed (or will be): lays the picture out again for width x height.
  void set_size(int width, int height);
  /// Keeps `pixels` at the bottom free of the surface and the legend (the explorer's controls).
  void set_bottom_reserved(int pixels);
  /// Where the title, legend and surface are (for the current size, options and range).
  const PictureLayout& layout() const;

  /// The colour range in use (see color_range) and the resolved colour map.
  double range_lo() const;
  double range_hi() const;
  const std::string& color_map() const;

  /// The glyphs drawn (or that would be drawn) for the current surface and options.
  vtkPolyData* glyphs();

  /// Points the camera: options().camera when set, else fit_camera_to_points on the mesh's
  /// framing points (or, when `bounds` is given, fit_camera on that box: screen-space mode
  /// before any mesh) with options().view and the aspect of layout().surface; returns the camera
  /// it set.
  Camera frame_camera(const std::array<double, 6>* bounds = nullptr);
  /// The 3D renderer's current camera (after the user moved it, say) as plain data.
  Camera current_camera() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Sets the renderer's active camera to `cam` and resets the clipping range.
void apply_camera(vtkRenderer* renderer, const Camera& cam);

}  // namespace isocurv::viz
