#include "deform/affine.h"

#include <cmath>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "deform/detail/deform_program.h"

namespace isocurv::deform {

Affine scaling(double a, double b, double c) {
  return {float(a), 0, 0, 0, 0, float(b), 0, 0, 0, 0, float(c), 0};
}

Affine rotation(const std::array<double, 3>& axis, double angle) {
  const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  const double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;  // Rodrigues
  return {float(t * x * x + c),     float(t * x * y - s * z), float(t * x * z + s * y), 0,
          float(t * x * y + s * z), float(t * y * y + c),     float(t * y * z - s * x), 0,
          float(t * x * z - s * y), float(t * y * z + s * x), float(t * z * z + c),     0};
}

std::array<double, 3> ellipsoid_axes(double t) {
  const double w = 2 * 3.14159265358979323846;
  return {1 + 0.5 * std::sin(w * t), 1 + 0.5 * std::sin(w * t + w / 3),
          1 + 0.5 * std::sin(w * t + 2 * w / 3)};
}

void affine(Device& device, const cl::Buffer& rest, std::size_t vertex_count, const Affine& m,
            cl::Buffer& out) {
  detail::DeformKernels& k = detail::deform_kernels(device);
  std::lock_guard<std::mutex> lock(k.mutex);
  device_call(device, "deform: affine", [&] {
    cl::CommandQueue& q = device.queue();
    q.enqueueWriteBuffer(k.matrix, CL_TRUE, 0, sizeof(Affine), m.data());
    set_args(k.affine, rest, cl_uint(vertex_count), k.matrix, out);
    launch(q, k.affine, vertex_count, detail::kGroup);
  });
}

Positions affine_reference(const Positions& rest, const Affine& m) {
  Positions out(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const float x = rest[i][0], y = rest[i][1], z = rest[i][2];
    for (int r = 0; r < 3; ++r)
      out[i][r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
  }
  return out;
}

}  // namespace isocurv::deform
