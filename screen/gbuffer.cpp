#include "screen/gbuffer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/vec3.h"

namespace isocurv::screen {
namespace {

using V = std::array<double, 3>;
using vec3::sub;
using vec3::dot;
using vec3::cross;
V unit(const V& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? V{a[0] / n, a[1] / n, a[2] / n} : V{0, 0, 0};
}

}  // namespace

void ViewFrame::ray(double x, double y, std::array<double, 3>& origin,
                    std::array<double, 3>& dir) const {
  const double aspect = double(width) / height;
  const double sx = ((x / width) * 2 - 1) * aspect * half_height;
  const double sy = ((y / height) * 2 - 1) * half_height;
  if (ortho) {
    for (int c = 0; c < 3; ++c) origin[c] = eye[c] + sx * right[c] + sy * up[c];
    dir = forward;
  } else {
    origin = eye;
    dir = unit({forward[0] + sx * right[0] + sy * up[0], forward[1] + sx * right[1] + sy * up[1],
                forward[2] + sx * right[2] + sy * up[2]});
  }
}

double ViewFrame::eye_depth(const std::array<double, 3>& p) const {
  return dot(sub(p, eye), forward);
}

bool ViewFrame::project(const std::array<double, 3>& p, double& x, double& y, double& depth) const {
  const V d = sub(p, eye);
  depth = dot(d, forward);
  double sx = dot(d, right), sy = dot(d, up);
  if (!ortho) {
    if (!(depth > 0)) return false;
    sx /= depth, sy /= depth;
  }
  const double aspect = double(width) / height;
  x = (sx / (aspect * half_height) + 1) / 2 * width;
  y = (sy / half_height + 1) / 2 * height;
  return true;
}

double ViewFrame::pixel_size(double depth) const {
  return 2 * half_height * (ortho ? 1.0 : depth) / height;
}

ViewFrame view_frame(const Camera& camera, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw Error("screen: image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is outside 1x1 .. " + std::to_string(kMaxImageSide) + "x" +
                std::to_string(kMaxImageSide));
  ViewFrame f;
  f.width = width, f.height = height, f.ortho = camera.ortho;
  f.eye = camera.position;
  f.forward = unit(sub(camera.focal_point, camera.position));
  if (dot(f.forward, f.forward) == 0) throw Error("screen: the camera sits on its focal point");
  f.right = unit(cross(f.forward, camera.view_up));
  if (dot(f.right, f.right) == 0) throw Error("screen: the camera's view up is along its view");
  f.up = cross(f.right, f.forward);
  f.half_height =
      camera.ortho ? camera.parallel_scale : std::tan(camera.view_angle_deg * M_PI / 360.0);
  return f;
}

void GBuffer::reset(const ViewFrame& f) {
  frame = f;
  const std::size_t n = pixels();
  position.assign(n, Vec3f{0, 0, 0});
  normal.assign(n, Vec3f{0, 0, 0});
  depth.assign(n, 0.0f);
  valid.assign(n, 0);
}

std::size_t GBuffer::valid_count() const {
  return std::size_t(std::count(valid.begin(), valid.end(), std::uint8_t(1)));
}

void depth_range(const ViewFrame& frame, const std::array<double, 6>& b, double& near,
                 double& far) {
  double lo = 1e300, hi = -1e300;
  for (int i = 0; i < 8; ++i) {
    const double z = frame.eye_depth({b[i & 1], b[2 + ((i >> 1) & 1)], b[4 + ((i >> 2) & 1)]});
    lo = std::min(lo, z), hi = std::max(hi, z);
  }
  const double pad = 0.01 * std::max(hi - lo, 1e-9);
  far = hi + pad;
  near = lo - pad;
  if (!frame.ortho) {
    far = std::max(far, 1e-6);
    near = std::max(near, far * 1e-3);
  }
}

std::vector<float> view_shading(const GBuffer& g) {
  std::vector<float> shade(g.pixels(), 1.0f);
  for (int y = 0; y < g.height(); ++y)
    for (int x = 0; x < g.width(); ++x) {
      const std::size_t i = std::size_t(x) + std::size_t(g.width()) * y;
      if (!g.valid[i]) continue;
      std::array<double, 3> origin, dir;
      g.frame.ray(x + 0.5, y + 0.5, origin, dir);
      const Vec3f& n = g.normal[i];
      // render's Lambert headlight (viz/curvature_scene.cpp: ambient 0.15, diffuse 0.85)
      shade[i] = float(0.15 + 0.85 * std::abs(n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]));
    }
  return shade;
}

}  // namespace isocurv::screen
