#pragma once
// Animated analytic fields: one Field per moment t, each frame's isosurface with exactly known
// curvature (datasets/exact_curvature.h works on every frame), for testing and benchmarking
// time series. Time t is in periods: every animation is periodic with period 1.
//
//   pulsing_sphere  |p| - R(t), R(t) = 0.6 + 0.2 sin(2 pi t) (signed distance, level set, inside
//                   Below), box [-1,1]^3: H = 1/R(t), K = 1/R(t)^2 on every frame.
//   gyroid_phase    sin(wx + 2 pi t)cos(wy) + sin(wy)cos(wz) + sin(wz)cos(wx + 2 pi t), w = 2 pi:
//                   the bundled gyroid moved by -t along x (a phase), iso 0, inside Above, cut by
//                   [-1,1]^3.
//   metaballs       sum of 5 Gaussians exp(-d^2 / (2 s^2)), s = 0.22, iso 0.5, inside Above, whose
//                   centres run on Lissajous paths c_i(t) = 0.45 (sin(2 pi (a_i t + p_i)),
//                   sin(2 pi (b_i t + q_i)), sin(2 pi (c_i t + r_i))) with small integer a, b, c
//                   (periodic in t), box [-1,1]^3: blobs that merge and split.
#include <memory>
#include <string>
#include <vector>

#include "datasets/field.h"

namespace isocurv::datasets {

/// Names accepted by make_animated_field: pulsing_sphere, gyroid_phase, metaballs.
std::vector<std::string> animated_field_names();

/// The named animation at time `t` (periods; any finite t). The Field's name() is the
/// animation's name; description() gives the formula and t.
/// @throw Error for an unknown name (listing the known ones) or a non-finite t.
std::unique_ptr<Field> make_animated_field(const std::string& name, double t);

/// The radius of pulsing_sphere at time t: 0.6 + 0.2 sin(2 pi t).
double pulsing_sphere_radius(double t);

}  // namespace isocurv::datasets
