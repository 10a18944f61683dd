#pragma once
// deform::noise_displace: displacement along the normal by a smooth noise field (Batagelo & Wu's
// Fig. 1, a noise-deformed sphere; Griffin's bump-mapped demo), written on the device.
// Tested in tests/deform/deform_fixtures.h, tests/deform/deformers_test.cpp.
#include <cstddef>
#include <vector>

#include "core/cl_device.h"
#include "core/mesh.h"

namespace isocurv::deform {

/// The noise field: the mean of 8 plane waves sin(frequency * d_k . p + phi_k) with fixed unit
/// directions d_k (a Fibonacci spiral over the sphere) and phases phi_k, so noise(p) lies in
/// [-1, 1], is infinitely smooth and band-limited at `frequency` (radians per world unit).
/// Deterministic: the same everywhere, every run. Double precision.
double smooth_noise(double x, double y, double z, double frequency);

/// out[i] = rest[i] + amplitude * noise(rest[i]) * normals[i] for the first vertex_count packed
/// float3 positions and unit normals (the rest pose's), on `device` (deform_kernels.cl:
/// noise_displace; the noise evaluated in float). Enqueued only. `amplitude` in world units.
/// @throw isocurv::Error on an OpenCL failure
void noise_displace(Device& device, const cl::Buffer& rest, const cl::Buffer& normals,
                    std::size_t vertex_count, double frequency, double amplitude, cl::Buffer& out);

/// The C++ reference of noise_displace() (noise in double, result rounded to float).
Positions noise_displace_reference(const Positions& rest, const std::vector<Vec3f>& normals,
                                   double frequency, double amplitude);

}  // namespace isocurv::deform
