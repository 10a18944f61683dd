// The volume estimator on an OpenCL device (see volume_estimate.h; the reference is
// volume_reference.cpp).
#include "curvature/volume_estimate.h"

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/cl_launch.h"
#include "core/cl_scratch.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/detail/volume_setup.h"
#include "curvature/tolerances.h"
#include "volume/brick_gather.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const volume_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature {
namespace {

enum Slot : std::size_t {
  kPositions,
  kPool,
  kTable,
  kFrame,
  kNormals,
  kK1,
  kK2,
  kDir1,
  kDir2,
  kH,
  kK,
  kDcurv,
  kShape,
  kCurved,
  kAo,
  kGradientNorm,
  kMissed,
  kSlots
};

constexpr std::size_t kGroup = 64;  // work-group size of the launch (core/cl_launch.h)
constexpr int kMaxTaps = volume::AxisWeights::kMaxTaps;

std::string build_options() {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "-DPIVOT_TOLERANCE=%.9g -DOPPOSITE_NORMALS=%.9g -DAO_C0=%.9g -DAO_C1=%.9g "
                "-DAO_C2=%.9g -DAO_SMIN=%.9g -DMAX_TAPS=%d -DGAUSSIAN_RADIUS=%.9g "
                "-DFIRST_ORDER_RADIUS=%.9g -DNEWTON_STEPS=%d -DON_SURFACE_VOXELS=%.9g "
                "-DMAX_FINAL_STEP_VOXELS=%.9g",
                kPivotTolerance, kOppositeNormals, kAoC0, kAoC1, kAoC2, kAoSMin, kMaxTaps,
                volume::kGaussianRadius, volume::kFirstOrderRadius, kNewtonSteps,
                kOnSurfaceVoxels, kMaxFinalStepVoxels);
  return buf;
}

// What the volume estimator keeps on one device between calls (Device::state).
struct VolumeSession {
  explicit VolumeSession(Device& device) : buffers(device, kSlots) {
    static const std::string source =
        std::string(kernels::curvature_math_cl) + "\n" + kernels::volume_kernels_cl;
    cl::Program& program = device.program("volume_curvature", source.c_str(), build_options());
    kernel = cl::Kernel(program, "volume_curvature");
  }
  std::mutex mutex;  // one estimate at a time per device (kernel arguments are shared state)
  ScratchBuffers buffers;
  cl::Kernel kernel;
  cl::Buffer& get(Slot slot, std::size_t bytes) {
    return buffers.get(slot, std::max<std::size_t>(bytes, 16));
  }
};

VolumeSession& session_for(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<VolumeSession>();
}

template <class T, class A>
cl::Buffer& upload(cl::CommandQueue& q, VolumeSession& s, Slot slot, const std::vector<T, A>& v) {
  cl::Buffer& b = s.get(slot, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b, CL_FALSE, 0, v.size() * sizeof(T), v.data());
  return b;
}

template <class T>
void download(cl::CommandQueue& q, cl::Buffer& b, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  if (n) q.enqueueReadBuffer(b, CL_FALSE, 0, n * sizeof(T), v.data());
}

// One evaluation at setup.sigma for `positions` (detail::VolumeEvaluate); `s` is locked.
detail::VolumeEvaluation evaluate(const Positions& positions, const volume::Volume& volume,
                                  const detail::VolumeSetup& setup, float isovalue, float ao_scale,
                                  Device& device, VolumeSession& s) {
  const std::size_t nv = positions.size();
  detail::VolumeEvaluation e;
  if (nv == 0) return e;
  const volume::GridFrame& fr = setup.frame;
  // Every voxel a vertex's filters can read: the taps' reach plus the largest Newton move.
  openvdb::Vec3d reach, deviation;
  for (int a = 0; a < 3; ++a) {
    deviation[a] = setup.sigma / fr.spacing[a];
    reach[a] = volume::kGaussianRadius * deviation[a] + setup.max_shift / fr.spacing[a] + 1;
  }
  const volume::BrickGather gather = volume::gather_bricks(*volume.grid, fr, positions, reach);
  const openvdb::Vec3d region = fr.to_world(openvdb::Vec3d(gather.origin.asVec3d()));
  std::vector<float> frame(15);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) frame[3 * r + c] = float(fr.B(r, c));
  for (int a = 0; a < 3; ++a) frame[9 + a] = float(region[a]), frame[12 + a] = float(deviation[a]);
  const openvdb::Coord lo = fr.lo - gather.origin, hi = fr.hi - gather.origin;

  cl::CommandQueue& q = device.queue();
  cl::Buffer& pos = upload(q, s, kPositions, positions);
  cl::Buffer& pool = upload(q, s, kPool, gather.samples);
  cl::Buffer& table = upload(q, s, kTable, gather.table);
  cl::Buffer& params = upload(q, s, kFrame, frame);
  cl::Buffer* f1[] = {&s.get(kK1, nv * 4), &s.get(kK2, nv * 4),          &s.get(kH, nv * 4),
                      &s.get(kK, nv * 4),  &s.get(kShape, nv * 4),       &s.get(kCurved, nv * 4),
                      &s.get(kAo, nv * 4), &s.get(kGradientNorm, nv * 4)};
  cl::Buffer& normals = s.get(kNormals, nv * sizeof(Vec3f));
  cl::Buffer& dir1 = s.get(kDir1, nv * sizeof(Vec3f));
  cl::Buffer& dir2 = s.get(kDir2, nv * sizeof(Vec3f));
  cl::Buffer& dcurv = s.get(kDcurv, nv * sizeof(cl_float4));
  cl::Buffer& missed = s.get(kMissed, nv);
  const cl_int4 dims = {{gather.dims[0], gather.dims[1], gather.dims[2], 0}};
  const cl_int4 clo = {{lo[0], lo[1], lo[2], 0}}, chi = {{hi[0], hi[1], hi[2], 0}};
  const float sign = volume.inside == volume::Inside::Above ? -1.0f : 1.0f;
  set_args(s.kernel, pos, cl_uint(nv), pool, table, dims, clo, chi, cl_int(fr.clamp),
           cl_float(volume.grid->background()), params, cl_float(isovalue), cl_float(sign),
           cl_float(setup.max_shift), cl_float(setup.voxel), cl_float(ao_scale), normals, *f1[0],
           *f1[1], dir1, dir2, *f1[2], *f1[3], dcurv, *f1[4], *f1[5], *f1[6], *f1[7], missed);
  launch(q, s.kernel, nv, kGroup);
  CurvatureField& out = e.field;
  download(q, normals, out.normals, nv);
  download(q, *f1[0], out.k1, nv);
  download(q, *f1[1], out.k2, nv);
  download(q, dir1, out.dir1, nv);
  download(q, dir2, out.dir2, nv);
  download(q, *f1[2], out.H, nv);
  download(q, *f1[3], out.K, nv);
  download(q, dcurv, out.dcurv, nv);
  download(q, *f1[4], out.shape_index, nv);
  download(q, *f1[5], out.curvedness, nv);
  download(q, *f1[6], out.ao, nv);
  download(q, *f1[7], e.raw.gradient_norm, nv);
  download(q, missed, e.raw.missed, nv);
  q.finish();
  e.bricks = gather.bricks();
  return e;
}

CurvatureField run(const Mesh& mesh, const volume::Volume& volume, float isovalue, double sigma,
                   float ao_scale, Device& device, VolumeEstimateStats* stats, bool finer_scales) {
  const detail::VolumeSetup setup = detail::volume_setup(mesh, volume, sigma);
  if (!std::isfinite(ao_scale)) throw Error("curvature: ao_scale must be finite");
  if (mesh.positions.empty()) {
    if (stats) *stats = {};
    return {};
  }
  VolumeSession& s = session_for(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  std::size_t refined = 0;
  detail::VolumeEvaluation e = detail::evaluate_with_finer_scales(
      mesh, setup, finer_scales,
      [&](const Positions& positions, const detail::VolumeSetup& at) {
        return evaluate(positions, volume, at, isovalue, ao_scale, device, s);
      },
      refined);
  const std::size_t unreliable = detail::finish_volume_field(mesh, e.raw, ao_scale, e.field);
  if (stats) *stats = VolumeEstimateStats{unreliable, e.bricks, refined};
  return std::move(e.field);
}

}  // namespace

CurvatureField volume_estimate(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                               double sigma, float ao_scale, Device& device,
                               VolumeEstimateStats* stats, bool finer_scales) {
  try {
    return run(mesh, volume, isovalue, sigma, ao_scale, device, stats, finer_scales);
  } catch (const cl::Error& e) {
    try {
      device.queue().finish();
    } catch (const cl::Error&) {
    }
    throw Error(std::string("curvature: OpenCL call ") + e.what() + " failed on " +
                device.info().name + ": " + cl_error_name(e.err()));
  }
}

}  // namespace isocurv::curvature
