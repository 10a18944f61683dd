#include "deform/noise_displace.h"

#include <cmath>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "deform/detail/deform_program.h"

namespace isocurv::deform {

double smooth_noise(double x, double y, double z, double frequency) {
  double sum = 0;
  for (int k = 0; k < detail::kWaveCount; ++k) {
    const std::array<double, 4> w = detail::noise_wave(k);
    sum += std::sin(frequency * (w[0] * x + w[1] * y + w[2] * z) + w[3]);
  }
  return sum / detail::kWaveCount;
}

void noise_displace(Device& device, const cl::Buffer& rest, const cl::Buffer& normals,
                    std::size_t vertex_count, double frequency, double amplitude, cl::Buffer& out) {
  detail::DeformKernels& k = detail::deform_kernels(device);
  std::lock_guard<std::mutex> lock(k.mutex);
  device_call(device, "deform: noise displacement", [&] {
    set_args(k.noise, rest, normals, cl_uint(vertex_count), k.waves, cl_int(detail::kWaveCount),
             cl_float(frequency), cl_float(amplitude), out);
    launch(device.queue(), k.noise, vertex_count, detail::kGroup);
  });
}

Positions noise_displace_reference(const Positions& rest, const std::vector<Vec3f>& normals,
                                   double frequency, double amplitude) {
  if (normals.size() != rest.size())
    throw Error("deform: " + std::to_string(normals.size()) + " normals for " +
                std::to_string(rest.size()) + " positions");
  Positions out(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const double d = amplitude * smooth_noise(rest[i][0], rest[i][1], rest[i][2], frequency);
    for (int r = 0; r < 3; ++r) out[i][r] = float(rest[i][r] + d * normals[i][r]);
  }
  return out;
}

}  // namespace isocurv::deform
