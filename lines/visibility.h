#pragma once
// Hidden-line removal for vector output: an exact ray cast against the surface.
// Tested in tests/lines/test_svg_visibility.cpp.
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/mesh.h"
#include "lines/segments.h"

namespace isocurv::lines {

/// Casts rays from points on the surface towards the eye against the mesh's
/// triangles (VTK's vtkStaticCellLocator). Built once per mesh; the mesh is
/// copied. Not thread-safe.
class VisibilityTester {
public:
  explicit VisibilityTester(const Mesh &mesh);
  ~VisibilityTester();
  VisibilityTester(const VisibilityTester &) = delete;
  VisibilityTester &operator=(const VisibilityTester &) = delete;

  /// True when no triangle lies between the point `p` of face `face` and the
  /// eye (for an orthographic camera: along toward_camera() out of the mesh's
  /// box). The ray starts one mean edge length towards the eye and a twentieth
  /// of one along the face's normal (so the point's own and neighbouring
  /// facets, which a contour's ray grazes, do not hide it).
  bool visible(const Vec3f &p, std::uint32_t face, const Camera &camera) const;

  /// An occluding contour's segment: visible() at its midpoint, or else from a start
  /// kContourSideEdges mean edges to either side of the line in the image. The contour comes
  /// from smoothed normals, so on a noisy surface it runs a little inside the rim of the mesh's
  /// own facets, whose bumps would hide it in dashes; a line hidden by another part of the
  /// surface is hidden on both sides.
  bool visible_contour(const Segment &segment, const Camera &camera) const;

  /// Each segment's visibility: visible_contour() for contours, visible() at the midpoint for
  /// the other lines.
  std::vector<bool> visible_segments(const Segments &segments,
                                     const Camera &camera) const;

  /// How far (in mean edge lengths) visible_contour() looks to each side of a contour.
  static constexpr double kContourSideEdges = 1.5;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace isocurv::lines
