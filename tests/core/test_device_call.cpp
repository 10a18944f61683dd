// The device-error boundary (core/device_call.h): one wording, the queue drained before unwinding.
#include "core/device_call.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace isocurv {
namespace {

// A large non-blocking upload, so that it is likely still queued when the exception is thrown.
cl::Event queue_upload(Device& dev, cl::Buffer& buffer, const std::vector<float>& host) {
  buffer = cl::Buffer(dev.context(), CL_MEM_READ_WRITE, host.size() * sizeof(float));
  cl::Event done;
  dev.queue().enqueueWriteBuffer(buffer, CL_FALSE, 0, host.size() * sizeof(float), host.data(),
                                 nullptr, &done);
  return done;
}

TEST(DeviceCall, ReturnsWhatTheCallReturns) {
  Device& dev = Device::default_device();
  EXPECT_EQ(device_call(dev, "stage", [] { return 42; }), 42);
  int x = 1;
  int& r = device_call(dev, "stage", [&]() -> int& { return x; });
  EXPECT_EQ(&r, &x);
}

TEST(DeviceCall, AnOpenClFailureBecomesOneLineNamingStageCallDeviceAndCode) {
  Device& dev = Device::default_device();
  try {
    device_call(dev, "curvature: testing", [] { throw cl::Error(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel"); });
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "curvature: testing: OpenCL call clEnqueueNDRangeKernel failed on " +
                                         dev.info().name + ": CL_OUT_OF_RESOURCES");
  }
  try {
    device_call(dev, "volume.nrrd: marching cubes",
                [] { throw cl::Error(CL_INVALID_VALUE, "clCreateBuffer"); });
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("volume.nrrd: marching cubes: OpenCL call clCreateBuffer", 0), 0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("CL_INVALID_VALUE"), std::string::npos) << e.what();
  }
}

TEST(DeviceCall, OtherExceptionsGoOnUnchanged) {
  Device& dev = Device::default_device();
  EXPECT_THROW(device_call(dev, "stage", [] { throw std::invalid_argument("x"); }),
               std::invalid_argument);
  try {
    device_call(dev, "stage", [] { throw Error("file.raw", "truncated"); });
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "file.raw: truncated");
  }
}

TEST(DeviceCall, TheQueueIsDrainedBeforeTheErrorArrives) {
  Device& dev = Device::default_device();
  const std::vector<float> host(std::size_t(16) << 20, 1.0f);  // 64 MB, outlives the call
  cl::Buffer buffer;
  cl::Event done;
  EXPECT_THROW(device_call(dev, "stage",
                           [&] {
                             done = queue_upload(dev, buffer, host);
                             throw cl::Error(CL_OUT_OF_RESOURCES, "clEnqueueReadBuffer");
                           }),
               Error);
  EXPECT_EQ(done.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
}

TEST(DeviceCall, DrainOnUnwindDrainsBeforeLaterLocalsGoAndOnlyWhenUnwinding) {
  Device& dev = Device::default_device();
  cl::Buffer buffer;
  cl::Event done;
  try {
    const std::vector<float> host(std::size_t(16) << 20, 2.0f);
    done = queue_upload(dev, buffer, host);
    const DrainOnUnwind drain(dev);  // destroyed before `host`
    throw std::runtime_error("unwinding");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(done.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>(), CL_COMPLETE);
  // Without an exception it does nothing (the caller decides when to wait).
  { const DrainOnUnwind quiet(dev); }
  dev.queue().finish();
}

}  // namespace
}  // namespace isocurv
