#pragma once
// Shared helpers of the deform tests.
#include <cmath>
#include <cstddef>

#include "core/cl_device.h"
#include "core/mesh.h"
#include "deform/noise_displace.h"
#include "tests/curvature/test_meshes.h"

namespace isocurv::test {

/// The device the suite runs on (the process default: PoCL here).
inline Device& device() { return Device::default_device(); }

/// Copies host positions into a fresh device buffer.
inline cl::Buffer to_device(const Positions& p) {
  cl::Buffer b(device().context(), CL_MEM_READ_WRITE, std::max<std::size_t>(p.size() * 12, 16));
  if (!p.empty()) device().queue().enqueueWriteBuffer(b, CL_TRUE, 0, p.size() * 12, p.data());
  return b;
}

/// Reads n positions back from a device buffer.
inline Positions from_device(const cl::Buffer& b, std::size_t n) {
  Positions p(n);
  if (n) device().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * 12, p.data());
  return p;
}

/// Largest coordinate difference between two position arrays.
inline double max_difference(const Positions& a, const Positions& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) d = std::max(d, double(std::abs(a[i][k] - b[i][k])));
  return d;
}

/// A lumpy closed mesh: an icosphere whose radius varies smoothly (no two vertices alike).
inline Mesh lumpy_sphere(int level) {
  Mesh m = icosphere(level);
  for (Vec3f& p : m.positions) {
    const double s = 1 + 0.15 * deform::smooth_noise(p[0], p[1], p[2], 3.0);
    for (float& c : p) c = float(c * s);
  }
  return m;
}

/// A fan of `n` triangles around a raised apex (vertex 0 has n corners, more than the kernels'
/// 8-corner register path) with an open rim: large fans and boundary vertices.
inline Mesh cone_fan(int n) {
  Mesh m;
  m.positions.push_back({0, 0, 0.5f});
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979 * i / n;
    m.positions.push_back({float(std::cos(a)), float(std::sin(a)), float(0.1 * std::sin(3 * a))});
  }
  for (int i = 0; i < n; ++i)
    m.triangles.push_back({0, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % n)});
  return m;
}

}  // namespace isocurv::test
