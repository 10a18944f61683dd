#include "core/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/vec3.h"

namespace isocurv {
namespace {

using Vec = std::array<double, 3>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kIsoAzimuthDeg = 35;    // the iso view: from -y, turned about +z ...
constexpr double kIsoElevationDeg = 30;  // ... then raised

using vec3::add;
using vec3::sub;
using vec3::scale;
using vec3::dot;
using vec3::cross;
using vec3::normalized;

/// Rodrigues: `v` turned by `deg` degrees about the unit `axis` (right-handed).
Vec rotate(const Vec& v, const Vec& axis, double deg) {
  const double a = deg * kPi / 180, c = std::cos(a), s = std::sin(a);
  return add(add(scale(v, c), scale(cross(axis, v), s)), scale(axis, dot(axis, v) * (1 - c)));
}

/// vtkCamera::Azimuth: the camera turns about the view up through the focal point.
void azimuth(Vec& toward, const Vec& up, double deg) { toward = rotate(toward, up, deg); }

/// vtkCamera::Elevation: the camera turns about (toward camera) x (view up), so it rises for
/// positive angles; the view up turns with it.
void elevation(Vec& toward, Vec& up, double deg) {
  const Vec axis = normalized(cross(toward, up));
  toward = rotate(toward, axis, deg);
  up = rotate(up, axis, deg);
}

}  // namespace

NamedView parse_named_view(const std::string& name) {
  static const std::pair<const char*, NamedView> kNames[] = {
      {"iso", NamedView::iso},     {"+x", NamedView::plus_x},  {"-x", NamedView::minus_x},
      {"+y", NamedView::plus_y},   {"-y", NamedView::minus_y}, {"+z", NamedView::plus_z},
      {"-z", NamedView::minus_z}};
  for (const auto& [n, v] : kNames)
    if (name == n) return v;
  throw Error("unknown view '" + name + "' (expected iso, +x, -x, +y, -y, +z or -z)");
}

std::string to_string(NamedView v) {
  switch (v) {
    case NamedView::iso: return "iso";
    case NamedView::plus_x: return "+x";
    case NamedView::minus_x: return "-x";
    case NamedView::plus_y: return "+y";
    case NamedView::minus_y: return "-y";
    case NamedView::plus_z: return "+z";
    case NamedView::minus_z: return "-z";
  }
  return "iso";
}

std::array<double, 3> Camera::toward_camera() const {
  return normalized(sub(position, focal_point));
}

std::array<double, 3> Camera::view_vector(const std::array<double, 3>& p) const {
  return ortho ? toward_camera() : normalized(sub(position, p));
}

std::optional<AnatomicalFrame> anatomical_frame_named(const std::string& letters) {
  if (letters == "RAS") return AnatomicalFrame::ras;
  if (letters == "LPS") return AnatomicalFrame::lps;
  if (letters == "LAS") return AnatomicalFrame::las;
  return std::nullopt;
}

bool is_anatomical_view(const std::string& name) {
  for (const char* n : {"anterior", "posterior", "left", "right", "superior", "inferior"})
    if (name == n) return true;
  return false;
}

std::pair<Vec, Vec> anatomical_axes(const std::string& name, AnatomicalFrame frame) {
  // World directions of the patient's right, anterior and superior.
  const double sx = frame == AnatomicalFrame::ras ? 1 : -1;  // LPS and LAS: +x is left
  const double sy = frame == AnatomicalFrame::lps ? -1 : 1;  // LPS: +y is posterior
  const Vec right{sx, 0, 0}, anterior{0, sy, 0}, superior{0, 0, 1};
  if (name == "anterior") return {anterior, superior};
  if (name == "posterior") return {scale(anterior, -1), superior};
  if (name == "right") return {right, superior};
  if (name == "left") return {scale(right, -1), superior};
  if (name == "superior") return {superior, anterior};
  if (name == "inferior") return {scale(superior, -1), anterior};
  if (name == "iso") {
    Vec toward = anterior, up = superior;
    azimuth(toward, up, kIsoAzimuthDeg);
    elevation(toward, up, kIsoElevationDeg);
    return {toward, up};
  }
  throw Error("unknown anatomical view '" + name +
              "' (expected anterior, posterior, left, right, superior or inferior)");
}

void view_axes(const ViewSpec& spec, Vec& toward, Vec& up) {
  const Vec z{0, 0, 1}, y{0, 1, 0};
  if (spec.axes) {
    toward = spec.axes->first;
    up = spec.axes->second;
  } else switch (spec.view) {
    case NamedView::iso:
      toward = {0, -1, 0};
      up = z;
      azimuth(toward, up, kIsoAzimuthDeg);
      elevation(toward, up, kIsoElevationDeg);
      break;
    case NamedView::plus_x: toward = {1, 0, 0}, up = z; break;
    case NamedView::minus_x: toward = {-1, 0, 0}, up = z; break;
    case NamedView::plus_y: toward = {0, 1, 0}, up = z; break;
    case NamedView::minus_y: toward = {0, -1, 0}, up = z; break;
    case NamedView::plus_z: toward = {0, 0, 1}, up = y; break;
    case NamedView::minus_z: toward = {0, 0, -1}, up = y; break;
  }
  if (spec.view_up) {
    const Vec u = normalized(*spec.view_up);
    const Vec t = normalized(toward);
    const Vec across = sub(u, scale(t, dot(u, t)));
    if (!(std::sqrt(dot(across, across)) > 1e-6))
      throw Error("--view-up lies along the viewing direction; choose another up or another view");
    up = normalized(across);
  }
  if (spec.azimuth_deg != 0) azimuth(toward, up, spec.azimuth_deg);
  if (spec.elevation_deg != 0) elevation(toward, up, spec.elevation_deg);
  toward = normalized(toward);
  up = normalized(sub(up, scale(toward, dot(up, toward))));
  // The up turned about the direction of projection (-toward): clockwise on screen, so the
  // picture turns anticlockwise for positive angles.
  if (spec.roll_deg != 0) up = normalized(rotate(up, scale(toward, -1), spec.roll_deg));
}

std::array<double, 3> parse_direction(const std::string& text) {
  static const std::pair<const char*, Vec> kAxes[] = {
      {"+x", {1, 0, 0}}, {"-x", {-1, 0, 0}}, {"+y", {0, 1, 0}},
      {"-y", {0, -1, 0}}, {"+z", {0, 0, 1}}, {"-z", {0, 0, -1}}};
  for (const auto& [n, v] : kAxes)
    if (text == n) return v;
  Vec v{};
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &tail) == 3 &&
      std::isfinite(v[0] + v[1] + v[2]) && dot(v, v) > 0)
    return normalized(v);
  throw Error("bad direction '" + text + "' (expected +x, -x, +y, -y, +z, -z or X,Y,Z)");
}

Camera fit_camera(const std::array<double, 6>& bounds, const ViewSpec& spec, double aspect,
                  double margin) {
  Vec lo{bounds[0], bounds[2], bounds[4]}, hi{bounds[1], bounds[3], bounds[5]};
  bool empty = false;
  for (int a = 0; a < 3; ++a) empty = empty || !(hi[a] >= lo[a]) || !std::isfinite(lo[a] + hi[a]);
  if (empty) lo = {-0.5, -0.5, -0.5}, hi = {0.5, 0.5, 0.5};
  if (!(std::sqrt(dot(sub(hi, lo), sub(hi, lo))) > 0)) {
    lo = sub(lo, {0.5, 0.5, 0.5});
    hi = add(hi, {0.5, 0.5, 0.5});
  }
  std::vector<Vec> corners(8);
  for (int i = 0; i < 8; ++i)
    corners[i] = {(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]};
  return fit_camera_to_points(corners, spec, aspect, margin);
}

Camera fit_camera_to_points(const std::vector<std::array<double, 3>>& points, const ViewSpec& spec,
                            double aspect, double margin) {
  Vec lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Vec& p : points)
    for (int a = 0; a < 3; ++a)
      if (std::isfinite(p[a])) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double diag = std::sqrt(dot(sub(hi, lo), sub(hi, lo)));
  if (points.empty() || !(hi[0] >= lo[0] && hi[1] >= lo[1] && hi[2] >= lo[2]) || !(diag > 0))
    return fit_camera({lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]}, spec, aspect, margin);
  if (!(aspect > 0)) aspect = 1;

  Camera cam;
  cam.ortho = spec.ortho;
  Vec toward, up;
  view_axes(spec, toward, up);
  const Vec right = cross(up, toward);  // image x to the right when looking along -toward
  cam.view_up = up;

  // The points in view coordinates (right, up, toward) about their box's centre; recentre so
  // the projection (for ortho exactly, for perspective nearly) is centred.
  const Vec centre = scale(add(lo, hi), 0.5);
  double rmin = 1e300, rmax = -1e300, umin = 1e300, umax = -1e300;
  for (const Vec& p : points) {
    const Vec d = sub(p, centre);
    const double r = dot(d, right), u = dot(d, up);
    if (!std::isfinite(r + u)) continue;
    rmin = std::min(rmin, r), rmax = std::max(rmax, r);
    umin = std::min(umin, u), umax = std::max(umax, u);
  }
  const double rc = 0.5 * (rmin + rmax), uc = 0.5 * (umin + umax);
  cam.focal_point = add(centre, add(scale(right, rc), scale(up, uc)));
  const double fill = 1 - std::clamp(margin, 0.0, 0.9);  // fraction of the half-size used
  const double zoom = spec.zoom > 0 ? spec.zoom : 1;

  if (spec.ortho) {
    const double half_h = std::max(0.5 * (umax - umin), 0.5 * (rmax - rmin) / aspect);
    cam.parallel_scale = std::max(half_h, 1e-12 * diag) / fill / zoom;
    cam.position = add(cam.focal_point, scale(toward, 2 * diag));
    return cam;
  }
  // Perspective: the distance D from the focal point at which every point (r, u, t) satisfies
  // |u| <= (D - t) tan(a/2) fill and |r| <= (D - t) tan(a/2) aspect fill.
  const double tan_half = std::tan(0.5 * cam.view_angle_deg * kPi / 180);
  double dist = 0;
  for (const Vec& p : points) {
    const Vec d = sub(p, centre);
    const double r = std::abs(dot(d, right) - rc), u = std::abs(dot(d, up) - uc), t = dot(d, toward);
    if (!std::isfinite(r + u + t)) continue;
    dist = std::max(dist, t + u / (tan_half * fill));
    dist = std::max(dist, t + r / (tan_half * aspect * fill));
  }
  dist = std::max(dist, 0.75 * diag);  // keep the eye outside the box
  cam.position = add(cam.focal_point, scale(toward, dist));
  cam.view_angle_deg = 2 * std::atan(tan_half / zoom) * 180 / kPi;
  return cam;
}

}  // namespace isocurv
