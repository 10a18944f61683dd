#pragma once
// Feature lines drawn over a curvature surface (render --lines, run --lines,
// the explorer's 'l').
// Tested through render --lines: tests/viz/test_render.cpp.
#include <memory>

#include "core/camera.h"
#include "lines/polylines.h"

class vtkCamera;
class vtkRenderer;

namespace isocurv::viz {

/// Polylines coloured by LineType (contours black, suggestive contours dark
/// grey, ridges red, valleys blue; opacity from Strength), drawn unlit, 2 pixels
/// wide over a white halo 4 pixels wide, so that they show on every colour map. Hidden lines are removed by the depth test
/// against the surface: adding the overlay turns on VTK's polygon offset for
/// every polygon mapper (VTK's global setting), which pushes surfaces back by
/// about a depth-buffer step per unit of slope, so lines lying on the surface
/// (contours at grazing angles included) pass the depth test while lines behind
/// it do not.
class LineOverlay {
public:
  LineOverlay();
  ~LineOverlay();
  LineOverlay(const LineOverlay &) = delete;
  LineOverlay &operator=(const LineOverlay &) = delete;

  /// Adds the actor to `renderer` (once).
  void add_to(vtkRenderer *renderer);
  /// Replaces the lines shown (copied).
  void set_lines(const lines::Polylines &lines);
  void set_visible(bool visible);
  bool visible() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The plain-data Camera of a vtkCamera (as apply_camera sets one).
Camera camera_of(vtkCamera *camera);

} // namespace isocurv::viz
