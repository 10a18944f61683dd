#pragma once
// deform::affine: an affine map of every vertex, written on the device (an analytic deformer
// with exact curvature: a unit sphere mesh scaled by diag(a, b, c) is an ellipsoid; a rotation
// is a rigid motion, the frame-coherence test's driver).
// Tested in tests/deform/animation_test.cpp, tests/deform/deformers_test.cpp.
#include <array>
#include <cstddef>

#include "core/cl_device.h"
#include "core/mesh.h"

namespace isocurv::deform {

/// A 3 x 4 affine matrix, row-major: p' = M[0..2][0..2] p + M[.][3] (world units).
using Affine = std::array<float, 12>;

/// diag(a, b, c) with no translation: the unit sphere becomes the ellipsoid of semi-axes a, b, c.
Affine scaling(double a, double b, double c);

/// The rotation by `angle` radians about the unit `axis` (right-handed), no translation.
Affine rotation(const std::array<double, 3>& axis, double angle);

/// The semi-axes of the affine ellipsoid animation at time t (one period per unit of t):
/// a = 1 + 0.5 sin 2 pi t, b = 1 + 0.5 sin(2 pi t + 2 pi / 3), c = 1 + 0.5 sin(2 pi t + 4 pi / 3),
/// all within [0.5, 1.5].
std::array<double, 3> ellipsoid_axes(double t);

/// out[i] = M rest[i] for the first `vertex_count` packed float3 positions of `rest`, on `device`
/// (deform_kernels.cl: affine_positions). Enqueued only (the device's queue is in order; finish
/// it before reading `out` on the host). rest and out may not alias.
/// @throw isocurv::Error on an OpenCL failure
void affine(Device& device, const cl::Buffer& rest, std::size_t vertex_count, const Affine& m,
            cl::Buffer& out);

/// The C++ reference of affine(), in float with the same order of operations.
Positions affine_reference(const Positions& rest, const Affine& m);

}  // namespace isocurv::deform
