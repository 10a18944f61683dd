#pragma once
// A VTK renderer showing one curvature surface: the coloured mesh, a scalar bar, optional
// direction glyphs and a title. Used by render_png and the explorer.
#include <memory>

#include "core/camera.h"
#include "core/mesh.h"
#include "curvature/curvature_field.h"
#include "viz/render_options.h"

class vtkRenderer;

namespace isocurv::viz {

class CurvatureScene {
 public:
  CurvatureScene();
  ~CurvatureScene();
  CurvatureScene(const CurvatureScene&) = delete;
  CurvatureScene& operator=(const CurvatureScene&) = delete;

  /// The renderer to add to a render window (owned by the scene).
  vtkRenderer* renderer() const;

  /// Shows `mesh` with `field` (copied), recoloured with the current options. An empty mesh shows
  /// nothing. Throws Error when the field's arrays do not match the vertex count, or (for a
  /// non-empty mesh) when it lacks the current colour quantity or, with AO on, the AO array.
  void set_surface(const Mesh& mesh, const curvature::CurvatureField& field);

  /// Applies colour quantity, AO, direction glyphs, clamp percentile and title (width and height
  /// are the window's business). Throws Error as set_surface does; the previous options stay.
  void set_options(const RenderOptions& options);
  const RenderOptions& options() const;

  /// The colour range in use (see color_range).
  double range_lo() const;
  double range_hi() const;

  /// Points the camera at the whole surface as options().view says (fit_camera with the
  /// window's aspect, options().width / options().height); returns the camera it set.
  Camera frame_camera();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Sets the renderer's active camera to `cam` and resets the clipping range.
void apply_camera(vtkRenderer* renderer, const Camera& cam);

}  // namespace isocurv::viz
