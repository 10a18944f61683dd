#pragma once
// The deformers' OpenCL program and kernels on one device (Device::state), and the work-group
// size of their launches.
#include <array>
#include <cstddef>
#include <mutex>
#include <string>

#include "core/cl_device.h"

namespace isocurv::deform::detail {

/// The noise field's plane waves (noise_displace.h): direction k (unit, a Fibonacci spiral) and
/// phase k, as (x, y, z, phase).
constexpr int kWaveCount = 8;
std::array<double, 4> noise_wave(int k);

struct DeformKernels {
  explicit DeformKernels(Device& device);
  std::mutex mutex;  ///< one launch at a time (kernel arguments and `matrix` are shared state)
  cl::Kernel affine, noise, skin;
  cl::Buffer matrix;  ///< 12 floats: affine()'s matrix, rewritten (blocking) per call
  cl::Buffer waves;   ///< kWaveCount float4: noise_wave() in float
};

/// The kernels of `device`, built on first use.
DeformKernels& deform_kernels(Device& device);

constexpr std::size_t kGroup = 64;

}  // namespace isocurv::deform::detail
