#include "features/detail/sampled_device.h"

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/cl_launch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "features/detail/volume_ball.h"

namespace isocurv::kernels {
extern const char* const dense_field_cl;
extern const char* const features_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::features::detail {
namespace {

/// What the features stage keeps on a device: the program and the last uploaded volume.
struct FeaturesState {
  explicit FeaturesState(Device& device) {
    static const std::string source =
        std::string(kernels::dense_field_cl) + "\n" + kernels::features_kernels_cl;
    char options[400];
    std::snprintf(options, sizeof options,
                  "-DWEB_STEPS=%d -DWEB_STEP_DIVISIONS=%d -DWEB_MAX_ATTEMPTS=%d "
                  "-DWEB_MAX_LENGTH=%.9ef -DPROJECT_STEPS=%d -DCORRECTOR_STEPS=%d "
                  "-DOFF_SURFACE=%.9ef -DMIN_COS=%.9ef -DARC_SAMPLES=%d -DREFINE_STEPS=%d",
                  kWebSteps, kWebStepDivisions, kWebMaxAttempts, kWebMaxLength, kProjectSteps,
                  kCorrectorSteps, kOffSurface, kMinCos, kArcSamples, kRefineSteps);
    cl::Program& program = device.program("features", source.c_str(), options);
    web = cl::Kernel(program, "features_web");
    ball = cl::Kernel(program, "features_ball");
  }
  std::mutex mutex;
  cl::Kernel web, ball;
  std::uint64_t uploaded = 0;  ///< DenseField::id of `values`
  cl::Buffer values, xform;
};

FeaturesState& state(Device& device) {
  return device_call(device, "features: building the kernels",
                     [&]() -> FeaturesState& { return device.state<FeaturesState>(); });
}

void upload_volume(Device& device, FeaturesState& s, const volume::DenseField& field) {
  if (s.uploaded == field.id) return;
  cl::Context& ctx = device.context();
  cl::CommandQueue& q = device.queue();
  s.values = cl::Buffer(ctx, CL_MEM_READ_ONLY, std::max<std::size_t>(4, field.values.size() * 4));
  q.enqueueWriteBuffer(s.values, CL_FALSE, 0, field.values.size() * 4, field.values.data());
  const std::array<float, 36> xf = field.device_transform();
  s.xform = cl::Buffer(ctx, CL_MEM_READ_ONLY, xf.size() * 4);
  q.enqueueWriteBuffer(s.xform, CL_TRUE, 0, xf.size() * 4, xf.data());
  s.uploaded = field.id;
}

/// The vertices' positions and normals as float4 buffers.
void upload_vertices(Device& device, const Mesh& mesh, const std::vector<Vec3f>& normals,
                     cl::Buffer& pos, cl::Buffer& nrm) {
  const std::size_t n = mesh.vertex_count();
  std::vector<cl_float4> p(std::max<std::size_t>(n, 1)), m(std::max<std::size_t>(n, 1));
  for (std::size_t i = 0; i < n; ++i) {
    p[i] = {{mesh.positions[i][0], mesh.positions[i][1], mesh.positions[i][2], 0}};
    m[i] = {{normals[i][0], normals[i][1], normals[i][2], 0}};
  }
  pos = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, p.size() * 16,
                   p.data());
  nrm = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, m.size() * 16,
                   m.data());
}

/// Launches k over n vertices in parts of kLaunchVertices, its argument `first_arg` the first
/// vertex of each part, reporting progress after each part finishes.
void launch_in_parts(Device& device, cl::Kernel& k, cl_uint first_arg, std::size_t n,
                     int work_group, const ProgressFn& progress) {
  for (std::size_t first = 0; first < n; first += kLaunchVertices) {
    const std::size_t count = std::min(kLaunchVertices, n - first);
    k.setArg(first_arg, cl_uint(first));
    launch(device.queue(), k, count, std::size_t(work_group));
    if (progress) {
      device.queue().finish();
      progress(count);
    }
  }
}

}  // namespace

std::vector<WebSums> web_on_device(Device& device, const volume::DenseField& field, float iso,
                                   const Mesh& mesh, const std::vector<Vec3f>& normals, double r,
                                   int azimuths, bool adaptive, double threshold,
                                   std::uint32_t seed, int work_group, const ProgressFn& progress) {
  const std::size_t n = mesh.vertex_count();
  std::vector<WebSums> out(n);
  if (n == 0) return out;
  FeaturesState& s = state(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  std::vector<cl_float4> host(n);  // outside device_call: read into until the queue drains
  std::vector<std::uint8_t> host_flags(n);
  device_call(device, "features: features_web", [&] {
    upload_volume(device, s, field);
    cl::Buffer pos, nrm;
    upload_vertices(device, mesh, normals, pos, nrm);
    cl::Buffer res(device.context(), CL_MEM_WRITE_ONLY, n * 16);
    cl::Buffer flags(device.context(), CL_MEM_WRITE_ONLY, n);
    set_args(s.web, s.values, cl_int4{{field.nx, field.ny, field.nz, field.sparse ? 1 : 0}}, cl_float(iso),
             cl_float(field.sign), s.xform, cl_float(field.shortest_voxel_edge()), pos, nrm,
             cl_uint(n), cl_float(r), cl_int(azimuths), cl_int(adaptive ? 1 : 0),
             cl_float(threshold), cl_uint(seed), res, flags);
    launch_in_parts(device, s.web, 16, n, work_group, progress);
    device.queue().enqueueReadBuffer(res, CL_FALSE, 0, n * 16, host.data());
    device.queue().enqueueReadBuffer(flags, CL_TRUE, 0, n, host_flags.data());
    for (std::size_t i = 0; i < n; ++i) {
      out[i].lbe = host[i].s[0], out[i].nsv = host[i].s[1], out[i].disc_area = host[i].s[2];
      out[i].azimuths = int(host[i].s[3]);
      out[i].boundary = host_flags[i] != 0;
    }
  });
  return out;
}

BallOnDevice ball_on_device(Device& device, const volume::DenseField& field, float iso,
                            const Mesh& mesh, const std::vector<Vec3f>& normals, double r,
                            int azimuths, const std::vector<double>& nodes,
                            const std::vector<double>& weights, int work_group,
                            const ProgressFn& progress) {
  const std::size_t n = mesh.vertex_count();
  BallOnDevice out;
  out.vr.resize(n), out.h.resize(n), out.leaves.assign(n, 0);
  if (n == 0) return out;
  if (nodes.size() > 16) throw Error("features: at most 16 radial quadrature nodes");
  FeaturesState& s = state(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  std::vector<cl_float2> host(n);  // outside device_call: read into until the queue drains
  device_call(device, "features: features_ball", [&] {
    upload_volume(device, s, field);
    cl::Buffer pos, nrm;
    upload_vertices(device, mesh, normals, pos, nrm);
    std::vector<float> gl;
    for (double x : nodes) gl.push_back(float(x));
    for (double w : weights) gl.push_back(float(w));
    cl::Buffer glb(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, gl.size() * 4,
                   gl.data());
    cl::Buffer res(device.context(), CL_MEM_WRITE_ONLY, n * 8);
    std::vector<std::uint8_t> zero(n, 0);
    cl::Buffer flags(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, n, zero.data());
    set_args(s.ball, s.values, cl_int4{{field.nx, field.ny, field.nz, field.sparse ? 1 : 0}}, cl_float(iso),
             cl_float(field.sign), s.xform, glb, cl_int(azimuths), cl_int(nodes.size()), pos, nrm,
             cl_uint(n), cl_float(r), res, flags);
    launch_in_parts(device, s.ball, 14, n, work_group, progress);
    device.queue().enqueueReadBuffer(res, CL_FALSE, 0, n * 8, host.data());
    device.queue().enqueueReadBuffer(flags, CL_TRUE, 0, n, out.leaves.data());
    for (std::size_t i = 0; i < n; ++i) out.vr[i] = host[i].s[0], out.h[i] = host[i].s[1];
  });
  return out;
}

}  // namespace isocurv::features::detail
