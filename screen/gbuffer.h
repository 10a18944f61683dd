#pragma once
// The deferred G-buffer screen-space curvature reads: per pixel a surface point, its unit normal
// and its eye depth, for one camera. Filled by the volume ray caster (ray_cast.h) or the mesh
// rasteriser (rasterise.h); read by the estimators (estimate.h).
// Tested in tests/screen/scenes.h.
#include <array>
#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/mesh.h"

namespace isocurv::screen {

/// Largest image side accepted by every producer (pixels); larger sizes are an Error.
inline constexpr int kMaxImageSide = 8192;

/// The pixel rays of a Camera for a width x height image. Pixel (x, y) has its centre at
/// (x + 0.5, y + 0.5), y up from the image's bottom row (VTK display coordinates). Perspective:
/// every ray starts at the eye; the view angle is the full vertical angle (VTK's). Orthographic:
/// rays are parallel to `forward`, starting on the plane through the eye.
struct ViewFrame {
  std::array<double, 3> eye{}, forward{}, right{},
      up{};  ///< unit, right-handed (right x up = -forward)
  bool ortho = false;
  double half_height = 1;  ///< perspective: tan(angle / 2); ortho: parallel scale (world)
  int width = 0, height = 0;

  /// The ray through pixel centre (x, y): origin and unit direction (world).
  void ray(double x, double y, std::array<double, 3>& origin, std::array<double, 3>& dir) const;
  /// Eye depth of world point p: (p - eye) . forward.
  double eye_depth(const std::array<double, 3>& p) const;
  /// Pixel coordinates (x, y, continuous, centres at +0.5) and eye depth of world point p.
  /// Perspective points at eye depth <= 0 give false.
  bool project(const std::array<double, 3>& p, double& x, double& y, double& depth) const;
  /// World size of one pixel at eye depth `depth` (ortho: independent of it).
  double pixel_size(double depth) const;
};

/// The frame of `camera` for a width x height image. @throw Error for a size outside
/// [1, kMaxImageSide] or a degenerate camera (position on the focal point).
ViewFrame view_frame(const Camera& camera, int width, int height);

/// The G-buffer: row-major, index x + width * y, y up. Invalid pixels (no surface) hold zeros.
struct GBuffer {
  ViewFrame frame;
  double near = 0, far = 1;         ///< eye-depth range of the scene (clipping planes), near > 0
  std::vector<Vec3f> position;      ///< world position of the surface point
  std::vector<Vec3f> normal;        ///< unit outward normal
  std::vector<float> depth;         ///< eye depth (world units along `forward`)
  std::vector<std::uint8_t> valid;  ///< 1 where the pixel sees the surface

  int width() const { return frame.width; }
  int height() const { return frame.height; }
  std::size_t pixels() const { return std::size_t(frame.width) * frame.height; }
  /// Sized for `frame`, every pixel invalid.
  void reset(const ViewFrame& f);
  std::size_t valid_count() const;
};

/// Per pixel, the factor 0.15 + 0.85 |n . ray| (render's Lambert headlight) by which pictures
/// multiply a pixel's colour for a sense of shape (n the pixel's normal, ray its unit view direction); 1 where invalid.
std::vector<float> view_shading(const GBuffer& g);

/// The eye-depth range [near, far] of box `bounds` (xmin, xmax, ymin, ymax, zmin, zmax) seen by
/// `frame`, padded by 1%; near is kept >= far / 1000 (perspective) so window depth stays finite.
void depth_range(const ViewFrame& frame, const std::array<double, 6>& bounds, double& near,
                 double& far);

}  // namespace isocurv::screen
