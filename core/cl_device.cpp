#include "core/cl_device.h"

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <optional>

#include "core/cl_scratch.h"
#include "core/error.h"
#include "core/program_cache.h"

namespace isocurv {
namespace {

struct Found {
  DeviceInfo info;
  cl::Device device;
};

std::vector<Found> enumerate() {
  // The ICD loader (libOpenCL.so.1, Debian's ocl-icd-libopencl1) answers CL_PLATFORM_NOT_FOUND_KHR
  // (an exception here) when no driver is registered in /etc/OpenCL/vendors.
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    platforms.clear();
  }
  if (platforms.empty())
    throw NoOpenCL(
        "no OpenCL platform found: the OpenCL loader (ocl-icd-libopencl1) finds no driver; "
        "install one, e.g. apt-get install pocl-opencl-icd (CPU) or your GPU vendor's OpenCL ICD");
  std::vector<Found> out;
  for (auto& p : platforms) {
    std::vector<cl::Device> devs;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devs);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    for (auto& d : devs) {
      Found f;
      f.device = d;
      f.info.index = static_cast<int>(out.size());
      f.info.platform = p.getInfo<CL_PLATFORM_NAME>();
      f.info.name = d.getInfo<CL_DEVICE_NAME>();
      auto t = d.getInfo<CL_DEVICE_TYPE>();
      f.info.type = (t & CL_DEVICE_TYPE_GPU) ? "GPU" : (t & CL_DEVICE_TYPE_CPU) ? "CPU"
                    : (t & CL_DEVICE_TYPE_ACCELERATOR) ? "accelerator" : "other";
      f.info.version = d.getInfo<CL_DEVICE_VERSION>();
      f.info.global_memory = d.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      f.info.compute_units = d.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      out.push_back(f);
    }
  }
  if (out.empty())
    throw NoOpenCL(
        "OpenCL platforms exist but offer no device: apt-get install pocl-opencl-icd for a "
        "CPU device");
  return out;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> out;
  for (auto& f : enumerate()) out.push_back(f.info);
  return out;
}

std::shared_ptr<Device> Device::open(int index) {
  auto all = enumerate();
  if (index < 0) {
    if (const char* env = std::getenv("ISOCURV_DEVICE"); env && *env) {
      char* end = nullptr;
      long v = std::strtol(env, &end, 10);
      if (*end != '\0' || v < 0)
        throw Error("ISOCURV_DEVICE='" + std::string(env) + "' is not a device number (see isocurv devices)");
      index = static_cast<int>(v);
    }
  }
  if (index < 0) {
    for (auto& f : all)
      if (f.info.type == "GPU") { index = f.info.index; break; }
    if (index < 0)
      for (auto& f : all)
        if (f.info.type == "CPU") { index = f.info.index; break; }
    if (index < 0) index = 0;
  }
  if (index >= static_cast<int>(all.size()))
    throw Error("no OpenCL device number " + std::to_string(index) + " (there are " +
                std::to_string(all.size()) + "; see isocurv devices)");
  auto dev = std::make_shared<Device>();
  dev->info_ = all[index].info;
  dev->device_ = all[index].device;
  try {
    dev->driver_.driver_version = dev->device_.getInfo<CL_DRIVER_VERSION>();
    dev->driver_.platform_version =
        cl::Platform(dev->device_.getInfo<CL_DEVICE_PLATFORM>()).getInfo<CL_PLATFORM_VERSION>();
  } catch (const cl::Error&) {
    // left empty: the cache key still names the device and its version
  }
  try {
    dev->context_ = cl::Context(dev->device_);
    dev->queue_ = cl::CommandQueue(dev->context_, dev->device_);
  } catch (const cl::Error& e) {
    throw Error("cannot open OpenCL device '" + dev->info_.name + "': " + e.what() + " (" +
                cl_error_name(e.err()) + ")");
  }
  return dev;
}

Device& Device::default_device() {
  static std::shared_ptr<Device> dev;
  static std::mutex m;
  std::lock_guard<std::mutex> lock(m);
  if (!dev) dev = open(-1);
  return *dev;
}

cl::Program& Device::program(const std::string& name, const char* source, const std::string& options) {
  const std::string key = name + "|" + options;
  auto it = programs_.find(key);
  if (it != programs_.end()) return it->second;
  const auto t0 = std::chrono::steady_clock::now();
  const std::string build_options = options + " -cl-std=CL1.2";
  detail::ProgramKey cache_key;
  cache_key.name = name;
  cache_key.source_hash = detail::hash_hex(source);
  cache_key.options = build_options;
  cache_key.platform = info_.platform + " " + driver_.platform_version;
  cache_key.device = info_.name + " " + info_.version;
  cache_key.driver = driver_.driver_version;
  const std::string cache_dir = program_cache_dir();
  bool rejected = false;
  std::optional<cl::Program> built;
  if (auto binary = detail::load_program_binary(cache_dir, cache_key, &rejected)) {
    try {  // a binary the driver refuses (stale, corrupt past the checksum) is rebuilt below
      cl::Program prog(context_, {device_}, cl::Program::Binaries{*binary});
      prog.build({device_}, build_options.c_str());
      built = prog;
    } catch (const cl::Error&) {
      rejected = true;
    }
  }
  const bool from_cache = built.has_value();
  if (!built) {
    cl::Program prog(context_, std::string(source));
    try {
      prog.build({device_}, build_options.c_str());
    } catch (const cl::Error&) {
      std::string log;
      try {
        log = prog.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
      } catch (...) {
      }
      throw Error("OpenCL program '" + name + "' failed to build on " + info_.name + ":\n" + log);
    }
    built = prog;
    if (!cache_dir.empty()) {
      try {
        const auto binaries = prog.getInfo<CL_PROGRAM_BINARIES>();
        if (binaries.size() == 1) detail::store_program_binary(cache_dir, cache_key, binaries[0]);
      } catch (const cl::Error&) {
        // a driver that cannot return binaries: no cache, nothing else lost
      }
    }
  }
  detail::record_program_build(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
      from_cache, rejected);
  return programs_.emplace(key, *built).first->second;
}

cl::Kernel& Device::kernel(cl::Program& program, const char* name) {
  const auto key = std::make_pair(static_cast<const cl::Program*>(&program), std::string(name));
  auto it = kernels_.find(key);
  if (it != kernels_.end()) return it->second;
  return kernels_.emplace(key, cl::Kernel(program, name)).first->second;
}

Device::Device() = default;
Device::~Device() = default;

ScratchBuffers& Device::scratch() { return state<ScratchBuffers>(); }

std::string cl_error_name(int code) {
  switch (code) {
    case CL_SUCCESS: return "CL_SUCCESS";
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE: return "CL_INVALID_GLOBAL_WORK_SIZE";
    default: return "OpenCL error " + std::to_string(code);
  }
}

}  // namespace isocurv
