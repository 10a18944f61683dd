#pragma once
// The OpenCL device shared by every compute stage: device choice, queue, program builds.
// Tested in tests/core/scan_sort_test.cpp, tests/core/test_program_cache.cpp.
#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#define CL_HPP_ENABLE_EXCEPTIONS
#include <CL/opencl.hpp>

#include <map>
#include <memory>
#include <string>
#include <typeindex>
#include <utility>
#include <vector>

#include "core/error.h"

namespace isocurv {

class ScratchBuffers;

/// The Error list_devices() and Device::open() throw when there is no OpenCL platform or device
/// at all (no driver installed); its message names the Debian packages that provide one.
class NoOpenCL : public Error {
 public:
  using Error::Error;
};

/// One OpenCL device as `isocurv devices` lists it.
struct DeviceInfo {
  int index = -1;          ///< position in list_devices(), what --device takes
  std::string platform;    ///< platform name, e.g. "Portable Computing Language"
  std::string name;        ///< device name
  std::string type;        ///< "GPU", "CPU", "accelerator" or "other"
  std::string version;     ///< OpenCL version string of the device
  std::uint64_t global_memory = 0;  ///< bytes
  std::uint32_t compute_units = 0;
};

/// Every device on every platform, in a stable order. Throws NoOpenCL, naming the packages to
/// install, when no OpenCL platform or device exists.
std::vector<DeviceInfo> list_devices();

/// An opened device with its context and in-order queue. Programs are built once and cached.
class Device {
 public:
  /// Opens device `index` of list_devices(); index < 0 picks the default: the environment
  /// variable ISOCURV_DEVICE if set, else the first GPU, else the first CPU device (PoCL).
  static std::shared_ptr<Device> open(int index = -1);
  /// The process-wide default device (opened once, on first use).
  static Device& default_device();

  const DeviceInfo& info() const { return info_; }
  cl::Context& context() { return context_; }
  cl::CommandQueue& queue() { return queue_; }
  cl::Device& device() { return device_; }

  /// Builds (once; later calls return the cached program) `source` under `name`. The compiled
  /// binary is also kept on disk (core/program_cache.h) and later processes build from it instead
  /// of compiling. A failed build throws Error carrying the compiler's log.
  cl::Program& program(const std::string& name, const char* source, const std::string& options = "");

  /// Kernel `name` of `program` (one of this device's), created once and cached: creating kernels
  /// per call costs PoCL a reload of their compiled code. Callers set every argument before each
  /// launch (an enqueue keeps the values it was given). Like the queue, for one thread at a time.
  cl::Kernel& kernel(cl::Program& program, const char* name);

  /// The device's reusable scratch buffers (core/cl_scratch.h), the state<ScratchBuffers>() the
  /// mesher and the scans share. Like the queue, for one thread at a time.
  ScratchBuffers& scratch();

  /// The one place every stage keeps what it reuses on this device between calls (kernels, buffers,
  /// host storage): the object of type T, constructed as T(*this) on the first call and destroyed
  /// with the device, before its queue and context. One object per type and device; T is usually
  /// a stage's private struct. Like the queue, for one thread at a time (a T that must serialise
  /// its callers holds its own mutex).
  template <class T>
  T& state() {
    std::shared_ptr<void>& slot = states_[std::type_index(typeid(T))];
    if (!slot) slot = std::make_shared<T>(*this);
    return *static_cast<T*>(slot.get());
  }

  Device();
  ~Device();

 private:
  struct DriverInfo {
    std::string driver_version, platform_version;  ///< for the program cache's key
  };
  DeviceInfo info_;
  DriverInfo driver_;
  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::map<std::string, cl::Program> programs_;
  std::map<std::pair<const cl::Program*, std::string>, cl::Kernel> kernels_;
  std::map<std::type_index, std::shared_ptr<void>> states_;  // state<T>(), destroyed first
};

/// Rounds n up to a multiple of m (for global work sizes).
inline std::size_t round_up(std::size_t n, std::size_t m) { return (n + m - 1) / m * m; }

/// Human-readable name of an OpenCL error code, e.g. "CL_OUT_OF_RESOURCES".
std::string cl_error_name(int code);

}  // namespace isocurv
