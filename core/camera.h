#pragma once
// Where a picture or a line drawing is seen from: named views and a camera as plain data.
//
// Shared by everything that needs a viewpoint (viz renders, lines' contours and SVG output) so
// that a line drawing and a rendered PNG of the same options see the same thing. No VTK here;
// viz/ applies a Camera to a vtkCamera.
// Tested in tests/core/test_camera.cpp, tests/screen/scenes.h.
#include <array>
#include <vector>
#include <optional>
#include <string>
#include <utility>

namespace isocurv {

/// A named viewpoint. `+x` puts the camera on the +x side of the object's centre, looking at it
/// (towards -x), with +z up; `+z`/`-z` look along z with +y up. `iso` is the three-quarter view
/// from above: from -y turned 35 degrees about +z, then raised 30 degrees.
enum class NamedView { iso, plus_x, minus_x, plus_y, minus_y, plus_z, minus_z };

/// Parses "iso", "+x", "-x", "+y", "-y", "+z", "-z". @throw Error naming the choices.
NamedView parse_named_view(const std::string& name);
/// The name parse_named_view accepts for `v`.
std::string to_string(NamedView v);

/// How to choose the camera: a named view, turned further, zoomed, and the projection.
struct ViewSpec {
  NamedView view = NamedView::iso;
  double azimuth_deg = 0;    ///< then turned about the view up through the centre (as vtkCamera::Azimuth)
  double elevation_deg = 0;  ///< then raised about the horizontal axis (as vtkCamera::Elevation)
  double zoom = 1;           ///< > 1 magnifies (narrows the view angle, or the parallel scale)
  bool ortho = false;        ///< parallel projection instead of perspective
  /// When set: (toward camera, view up), unit and perpendicular, replacing `view` (anatomical
  /// views, anatomical_axes).
  std::optional<std::pair<std::array<double, 3>, std::array<double, 3>>> axes{};
  /// When set: the picture's up direction, replacing the view's own before the azimuth and
  /// elevation (made perpendicular to the viewing direction; along it is an Error).
  std::optional<std::array<double, 3>> view_up{};
  double roll_deg = 0;  ///< last, the picture turned this many degrees anticlockwise on screen
};

/// Parses a --view-up direction: +x -x +y -y +z -z, or three numbers X,Y,Z (not all zero).
/// @throw Error naming the choices.
std::array<double, 3> parse_direction(const std::string& text);

/// A camera in world units. Perspective: `view_angle_deg` is the full vertical angle (as VTK's).
/// Orthographic: `parallel_scale` is half the view's height in world units.
struct Camera {
  std::array<double, 3> position{0, 0, 1};
  std::array<double, 3> focal_point{0, 0, 0};
  std::array<double, 3> view_up{0, 1, 0};  ///< unit, perpendicular to the direction of projection
  bool ortho = false;
  double view_angle_deg = 30;
  double parallel_scale = 1;

  /// Unit vector from the focal point towards the camera.
  std::array<double, 3> toward_camera() const;
  /// Unit vector from `p` towards the eye: toward_camera() for ortho, else (position - p)/|..|.
  std::array<double, 3> view_vector(const std::array<double, 3>& p) const;
};

/// The anatomical frame of a volume's world coordinates. RAS: +x towards the patient's right,
/// +y anterior, +z superior (NIfTI). LPS: +x left, +y posterior, +z superior (DICOM, ITK,
/// MetaImage). LAS: +x left, +y anterior, +z superior (NRRD's left-anterior-superior).
enum class AnatomicalFrame { ras, lps, las };

/// The frame named by Volume::world_space's letters ("RAS", "LPS", "LAS"); nullopt otherwise.
std::optional<AnatomicalFrame> anatomical_frame_named(const std::string& letters);

/// The names anatomical_axes accepts: anterior, posterior, left, right, superior, inferior.
bool is_anatomical_view(const std::string& name);

/// The (toward camera, view up) of an anatomical view in `frame`: "anterior" puts the camera in
/// front of the patient (looking at the face) with superior up; "posterior" behind; "left" and
/// "right" on that side (lateral views), superior up; "superior" above, "inferior" below, with
/// anterior up; "iso" is the default three-quarter view of an anatomical volume: from the front,
/// turned 35 degrees towards the patient's left and raised 30 degrees, superior up. @throw Error
/// for another name.
std::pair<std::array<double, 3>, std::array<double, 3>> anatomical_axes(const std::string& name,
                                                                       AnatomicalFrame frame);

/// Unit vector from the object's centre towards the camera, and the view up, for `spec` (its
/// named view, or its axes; its view_up; turned by its azimuth and elevation, then rolled).
/// @throw Error when spec.view_up lies along the viewing direction.
void view_axes(const ViewSpec& spec, std::array<double, 3>& toward_camera,
               std::array<double, 3>& view_up);

/// The camera of `spec` that shows the whole box `bounds` (xmin, xmax, ymin, ymax, zmin, zmax)
/// in an image of width/height `aspect`, every corner of the box at least `margin` (a fraction
/// of the image's half-height or half-width) inside the image edges (before `zoom`). The box's
/// projection is centred. An empty or degenerate box gets a unit box around its centre.
Camera fit_camera(const std::array<double, 6>& bounds, const ViewSpec& spec, double aspect,
                  double margin = 0.08);

/// The camera of `spec` that shows every one of `points` (world units) as fit_camera shows a
/// box's corners: their projection centred, each at least `margin` inside the image edges. Fitted
/// to the points themselves rather than their box, an object that does not fill its box's corners
/// (the lobster seen from above at an angle) fills the picture. No points: fit_camera's unit box.
Camera fit_camera_to_points(const std::vector<std::array<double, 3>>& points, const ViewSpec& spec,
                            double aspect, double margin = 0.08);

}  // namespace isocurv
