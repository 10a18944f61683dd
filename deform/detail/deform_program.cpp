#include "deform/detail/deform_program.h"

#include <cmath>
#include <vector>

#include "core/device_call.h"
#include "core/error.h"

namespace isocurv::kernels {
extern const char* const deform_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::deform::detail {

DeformKernels::DeformKernels(Device& device) {
  cl::Program& program = device.program("deform", kernels::deform_kernels_cl);
  affine = cl::Kernel(program, "affine_positions");
  noise = cl::Kernel(program, "noise_displace");
  skin = cl::Kernel(program, "skin_positions");
  matrix = cl::Buffer(device.context(), CL_MEM_READ_ONLY, 12 * sizeof(float));
  std::vector<cl_float4> w(kWaveCount);
  for (int k = 0; k < kWaveCount; ++k) {
    const std::array<double, 4> d = noise_wave(k);
    w[k] = {{float(d[0]), float(d[1]), float(d[2]), float(d[3])}};
  }
  waves = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                     w.size() * sizeof(cl_float4), w.data());
}

std::array<double, 4> noise_wave(int k) {
  const double pi = 3.14159265358979323846;
  const double z = 1 - (2.0 * k + 1) / kWaveCount;
  const double r = std::sqrt(1 - z * z);
  const double phi = k * pi * (3 - std::sqrt(5.0));  // the golden angle
  const double phase = 2 * pi * std::fmod(k * 0.6180339887498949, 1.0);
  return {r * std::cos(phi), r * std::sin(phi), z, phase};
}

DeformKernels& deform_kernels(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device_call(device, "deform: building the deformers",
                     [&]() -> DeformKernels& { return device.state<DeformKernels>(); });
}

}  // namespace isocurv::deform::detail
