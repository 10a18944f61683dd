// The volume estimator on an OpenCL device (see volume_estimate.h; the reference is
// volume_reference.cpp).
#include "curvature/volume_estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include "core/cl_launch.h"
#include "core/cl_scratch.h"
#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "curvature/derived.h"
#include "curvature/detail/volume_setup.h"
#include "curvature/tolerances.h"
#include "volume/prefilter.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const volume_kernels_cl;
}  // namespace isocurv::kernels

namespace isocurv::curvature {
namespace {

enum Slot : std::size_t {
  kPositions,
  kPool0,  // kPool0 + n: stage n's samples (volume::SmoothingPlan::stages)
  kPool1,
  kPool2,
  kPool3,
  kTable0,  // kTable0 + n: stage n's brick table
  kTable1,
  kTable2,
  kTable3,
  kBricks1,  // kBricks1 + a: the output bricks of the pass along axis a
  kBricks2,
  kBricks3,
  kTaps0,  // kTaps0 + a: the prefilter along axis a
  kTaps1,
  kTaps2,
  kBlocks,  // the smoothed samples in padded blocks (pad_bricks)
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
  kShift,
  kSurface,
  kSlots
};

constexpr std::size_t kGroup = 64;  // work-group size of the launch (core/cl_launch.h)
// The padded blocks of pad_bricks: a brick's 8 voxels per axis plus the B-spline taps' reach
// around any cell in it (floor(q) - 2 .. floor(q) + 3, see volume::spline_weights).
constexpr int kPadBefore = 2;
constexpr int kPadded = 8 + kPadBefore + 3;

std::string build_options() {
  char buf[512];
  std::snprintf(
      buf, sizeof buf,
      "-DPIVOT_TOLERANCE=%.9g -DOPPOSITE_NORMALS=%.9g -DAO_C0=%.9g -DAO_C1=%.9g "
      "-DAO_C2=%.9g -DAO_SMIN=%.9g -DBRICK_VOXELS=512 -DBRICK_ROWS=64 "
      "-DSPLINE_TAPS=5 -DPADDED=%d -DPAD_BEFORE=%d -DPADDED_VOXELS=%d -DNEWTON_STEPS=%d "
      "-DSURFACE_Y1=%.9ef -DSURFACE_Y2=%.9ef -DMIN_CORRECTION=%.9ef",
      kPivotTolerance, kOppositeNormals, kAoC0, kAoC1, kAoC2, kAoSMin, kPadded, kPadBefore,
      kPadded * kPadded * kPadded, kNewtonSteps, kSurfaceY1, kSurfaceY2, kMinCorrection);
  return buf;
}

// What the volume estimator keeps on one device between calls (Device::state).
struct VolumeSession {
  explicit VolumeSession(Device& device) : buffers(device, kSlots) {
    static const std::string source =
        std::string(kernels::curvature_math_cl) + "\n" + kernels::volume_kernels_cl;
    cl::Program& program = device.program("volume_curvature", source.c_str(), build_options());
    kernel = cl::Kernel(program, "volume_curvature");
    smooth = cl::Kernel(program, "smooth_axis");
    pad = cl::Kernel(program, "pad_bricks");
  }
  std::mutex mutex;  // one estimate at a time per device (kernel arguments are shared state)
  ScratchBuffers buffers;
  cl::Kernel kernel, smooth, pad;
  cl::Buffer& get(Slot slot, std::size_t bytes) {
    return buffers.get(slot, std::max<std::size_t>(bytes, 16));
  }
};

VolumeSession& session_for(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<VolumeSession>();
}

// The kernel's maps from the distinct index-space derivatives of orders 2 and 3 to the world-space
// Hessian and third derivatives (frame_t in volume_kernels.cl), appended to `out` row by row:
// m2[e][f] = sum over the ordered index pairs (a, b) of f's orders of B(a, k) B(b, l) for the
// world pair e = (k, l); m3 likewise over ordered triples.
void append_world_maps(const openvdb::Mat3d& B, std::vector<float>& out) {
  using volume::kHessianAxes, volume::kThirdAxes;
  auto pair_of = [](int a, int b) {  // the distinct pair (index of kHessianAxes) of ordered (a, b)
    for (int f = 0; f < 6; ++f)
      if (std::min(a, b) == kHessianAxes[f][0] && std::max(a, b) == kHessianAxes[f][1]) return f;
    return -1;
  };
  auto triple_of = [](int a, int b, int c) {
    int v[3] = {a, b, c};
    std::sort(v, v + 3);
    for (int f = 0; f < 10; ++f)
      if (v[0] == kThirdAxes[f][0] && v[1] == kThirdAxes[f][1] && v[2] == kThirdAxes[f][2])
        return f;
    return -1;
  };
  double m2[6][6] = {}, m3[10][10] = {};
  for (int e = 0; e < 6; ++e)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        m2[e][pair_of(a, b)] += B(a, kHessianAxes[e][0]) * B(b, kHessianAxes[e][1]);
  for (int e = 0; e < 10; ++e)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          m3[e][triple_of(a, b, c)] +=
              B(a, kThirdAxes[e][0]) * B(b, kThirdAxes[e][1]) * B(c, kThirdAxes[e][2]);
  for (auto& row : m2)
    for (double v : row) out.push_back(float(v));
  for (auto& row : m3)
    for (double v : row) out.push_back(float(v));
}

using Clock = StepClock;

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

// The raw samples of one estimate, on the host and the device, gathered and uploaded once, for
// the widest plan: the first one pool_bricks sees, which the caller makes the widest (the first
// evaluation is at the largest scale unless the per-vertex choice plans its largest rung before
// it), so every later plan's bricks lie among its. Gathering them again per evaluation was the
// largest part of the per-vertex choice's cost (the gyroid's 628k vertices: 773 of 2585 ms).
struct RawPool {
  std::optional<volume::SmoothingPlan> widest;
  std::vector<float> samples;  // 512 per brick of widest's stage 0, in its order
};

// The raw samples' device buffer (`pool`) and `plan`'s stage-0 table remapped to their bricks in
// it, filling `raw` from `plan` first when it is empty. Throws isocurv::Error when a brick of
// `plan` is not in the widest plan (which would read the background silently).
std::vector<std::int32_t> pool_bricks(const volume::SmoothingPlan& plan, const volume::Volume& volume,
                                      RawPool& raw, cl::CommandQueue& q, VolumeSession& s,
                                      cl::Buffer*& pool) {
  if (!raw.widest) {
    raw.widest = plan;
    volume::gather_bricks(*volume.grid, plan.frame, plan.stages[0].bricks, raw.samples);
    pool = &s.get(kPool0, raw.samples.size() * sizeof(float));
    if (!raw.samples.empty())  // `raw` outlives the estimate's queue
      q.enqueueWriteBuffer(*pool, CL_FALSE, 0, raw.samples.size() * sizeof(float), raw.samples.data());
  } else {
    pool = &s.get(kPool0, raw.samples.size() * sizeof(float));  // the same size: kept as filled
  }
  const volume::SmoothingPlan& w = *raw.widest;
  const volume::BrickSet& set = plan.stages[0];
  std::vector<std::int32_t> table(set.table.size(), -1);
  for (const openvdb::Coord& b : set.bricks) {
    const std::int32_t slot = w.in_region(b) ? w.stages[0].table[w.cell(b)] : -1;
    if (slot < 0) throw Error("curvature: a smoothing plan reaches past the estimate's widest one");
    table[plan.cell(b)] = slot;
  }
  return table;
}

// One evaluation at setup.sigma for `positions` (detail::VolumeEvaluate); `s` is locked.
detail::VolumeEvaluation evaluate(const Positions& positions, const volume::Volume& volume,
                                  const detail::VolumeSetup& setup, float isovalue, float ao_scale,
                                  Device& device, VolumeSession& s, RawPool& raw) {
  const std::size_t nv = positions.size();
  detail::VolumeEvaluation e;
  if (nv == 0) return e;
  const volume::GridFrame& fr = setup.frame;
  Clock::time_point t = Clock::now();
  const volume::SmoothingPlan plan =
      volume::plan_smoothing(fr, positions, detail::spline_reach(setup), setup.sigma);
  e.steps.plan = lap(t);
  // The kernel measures positions from a fixed anchor, the brick holding the volume's first
  // voxel, not from the plan's first brick: the float rounding of a vertex's index position then
  // does not depend on which vertices share the plan, so a piece of a distributed surface
  // (core/surface_piece.h) gets the single process's values to the bit. The region's first
  // voxel less the anchor is a whole number, subtracted exactly.
  const openvdb::Coord first(plan.origin[0] * 8, plan.origin[1] * 8, plan.origin[2] * 8);
  const openvdb::Coord anchor(fr.lo[0] & ~7, fr.lo[1] & ~7, fr.lo[2] & ~7);
  const openvdb::Vec3d at = fr.to_world(openvdb::Vec3d(anchor.asVec3d()));
  std::vector<float> frame(12);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) frame[3 * r + c] = float(fr.B(r, c));
  for (int a = 0; a < 3; ++a) frame[9 + a] = float(at[a]);
  append_world_maps(fr.B, frame);
  for (int a = 0; a < 3; ++a) frame.push_back(float(first[a] - anchor[a]));
  const cl_int4 dims = {{plan.dims[0], plan.dims[1], plan.dims[2], 0}};
  const cl_float background = volume.grid->background();

  cl::CommandQueue& q = device.queue();
  cl::Buffer& pos = upload(q, s, kPositions, positions);
  cl::Buffer* pool = nullptr;
  const std::vector<std::int32_t> table0 = pool_bricks(plan, volume, raw, q, s, pool);
  e.steps.gather = lap(t);
  // Every host array stays alive until q.finish() below.
  upload(q, s, kTable0, table0);
  for (int n = 1; n < 4; ++n) upload(q, s, Slot(kTable0 + n), plan.stages[n].table);
  // The three passes of the prefilter: along x from stage 0 into stage 1, along y, along z.
  std::vector<cl_int4> bricks[3];
  std::vector<float> taps[3];
  for (int a = 0; a < 3; ++a) {
    const volume::BrickSet& out = plan.stages[a + 1];
    for (const openvdb::Coord& b : out.bricks) {
      const openvdb::Coord r = b - plan.origin;
      bricks[a].push_back({{r[0], r[1], r[2], 0}});
    }
    // smooth_axis's `spread`: the taps reversed with 7 zeros either side.
    const int radius = plan.taps[a].radius;
    taps[a].assign(2 * radius + 15, 0.0f);
    for (int k = 0; k <= 2 * radius; ++k) taps[a][2 * radius + 7 - k] = float(plan.taps[a].w[k]);
    cl::Buffer& from = a == 0 ? *pool
                              : s.get(Slot(kPool0 + a), plan.stages[a].bricks.size() * 512 * sizeof(float));
    cl::Buffer& to = s.get(Slot(kPool0 + a + 1), out.bricks.size() * 512 * sizeof(float));
    cl::Buffer& list = upload(q, s, Slot(kBricks1 + a), bricks[a]);
    cl::Buffer& weights = upload(q, s, Slot(kTaps0 + a), taps[a]);
    set_args(s.smooth, from, s.get(Slot(kTable0 + a), 0), dims, background, list,
             cl_uint(out.bricks.size()), to, cl_int(a), cl_int(fr.clamp),
             cl_int(fr.lo[a] - first[a]), cl_int(fr.hi[a] - first[a]), weights,
             cl_int(plan.taps[a].radius));
    launch(q, s.smooth, out.bricks.size() * 64, kGroup);
  }
  cl::Buffer& table = s.get(kTable3, 0);
  const std::size_t n3 = plan.stages[3].bricks.size(),
                    padded = std::size_t(kPadded) * kPadded * kPadded;
  cl::Buffer& blocks = s.get(kBlocks, n3 * padded * sizeof(float));
  set_args(s.pad, s.get(kPool3, 0), table, dims, background, s.get(kBricks3, 0), cl_uint(n3),
           blocks);
  launch(q, s.pad, n3 * kPadded * kPadded, kGroup);
  q.finish();
  e.steps.smooth = lap(t);
  cl::Buffer& params = upload(q, s, kFrame, frame);
  cl::Buffer* f1[] = {&s.get(kK1, nv * 4), &s.get(kK2, nv * 4),          &s.get(kH, nv * 4),
                      &s.get(kK, nv * 4),  &s.get(kShape, nv * 4),       &s.get(kCurved, nv * 4),
                      &s.get(kAo, nv * 4), &s.get(kGradientNorm, nv * 4)};
  cl::Buffer& normals = s.get(kNormals, nv * sizeof(Vec3f));
  cl::Buffer& dir1 = s.get(kDir1, nv * sizeof(Vec3f));
  cl::Buffer& dir2 = s.get(kDir2, nv * sizeof(Vec3f));
  cl::Buffer& dcurv = s.get(kDcurv, nv * sizeof(cl_float4));
  cl::Buffer& shift = s.get(kShift, nv * sizeof(float));
  cl::Buffer& surface = s.get(kSurface, nv * sizeof(Vec3f));
  const float sign = volume.inside == volume::Inside::Above ? -1.0f : 1.0f;
  set_args(s.kernel, pos, cl_uint(nv), blocks, table, dims, params, cl_float(isovalue),
           cl_float(sign), cl_float(ao_scale), cl_int(setup.point == VolumePoint::surface),
           cl_float(setup.max_shift()), cl_float(setup.sigma * setup.sigma), normals, *f1[0], *f1[1], dir1, dir2, *f1[2], *f1[3],
           dcurv, *f1[4], *f1[5], *f1[6], *f1[7], shift, surface);
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
  download(q, shift, e.raw.shift, nv);
  if (setup.point == VolumePoint::surface) download(q, surface, out.surface_points, nv);
  q.finish();
  e.steps.vertices = lap(t);
  e.bricks = 0;
  for (const volume::BrickSet& stage : plan.stages) e.bricks += stage.bricks.size();
  return e;
}

CurvatureField run(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                   const VolumeOptions& options, Device& device, VolumeEstimateStats* stats) {
  detail::VolumeSetup setup = detail::volume_setup(mesh, volume, options.sigma);
  setup.point = options.point;
  const float ao_scale = options.ao_scale;
  const SurfacePiece* piece = options.piece;
  if (!std::isfinite(ao_scale)) throw Error("curvature: ao_scale must be finite");
  if (mesh.positions.empty()) {
    if (stats) *stats = {};
    if (piece) {  // an empty piece still takes part in the pieces' reductions
      const std::optional<detail::AdaptiveScale> adaptive =
          detail::adaptive_of(options, setup, volume);
      if (const auto pilots = adaptive ? detail::pilot_scales(*adaptive, setup.sigma) : std::nullopt) {
        const std::vector<float> none;  // the choice's reductions
        choose_vertex_scales({}, adaptive->model, {pilots->p1, pilots->p2, &none, &none, &none, &none},
                             setup.floor, adaptive->hi, piece);
      }
      CurvatureField nothing;
      detail::finish_volume_field(mesh, VertexCorners{}, detail::RawVertex{},
                                  detail::ScaleLadder{}, options.finer_scales, ao_scale, nothing,
                                  piece);
    }
    return {};
  }
  const std::optional<detail::AdaptiveScale> adaptive = detail::adaptive_of(options, setup, volume);
  VolumeSession& s = session_for(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  double prefill_ms = 0;
  detail::ScaleLadder ladder;
  VertexCorners corners;  // built once: the cut and the areas both need them
  build_vertex_corners(mesh, corners);
  RawPool raw;
  if (adaptive) {
    // Every rung reads a subset of the largest scale's raw bricks: gather and upload those once.
    Clock::time_point t = Clock::now();
    const volume::SmoothingPlan plan =
        volume::plan_smoothing(setup.frame, mesh.positions,
                               detail::spline_reach(detail::with_sigma(setup, adaptive->hi)), adaptive->hi);
    cl::Buffer* pool = nullptr;
    pool_bricks(plan, volume, raw, device.queue(), s, pool);
    device.queue().finish();
    prefill_ms = lap(t);
  }
  detail::VolumeEvaluation e = detail::evaluate_with_finer_scales(
      mesh, corners, setup, options.finer_scales,
      [&](const Positions& positions, const detail::VolumeSetup& at) {
        return evaluate(positions, volume, at, isovalue, ao_scale, device, s, raw);
      },
      ladder, adaptive ? &*adaptive : nullptr);
  Clock::time_point t = Clock::now();
  const std::size_t unreliable = detail::finish_volume_field(
      mesh, corners, e.raw, ladder, options.finer_scales, ao_scale, e.field, piece);
  if (options.point == VolumePoint::vertex)
    e.field.surface_points = edge_surface_points(mesh, volume, e.field);
  e.steps.finish = lap(t);
  e.steps.gather += prefill_ms;
  if (stats)
    *stats = VolumeEstimateStats{unreliable, e.bricks, ladder.refined,
                                 detail::count_of(ladder.outside), ladder.blur, e.steps};
  return std::move(e.field);
}

}  // namespace

CurvatureField volume_estimate(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                               const VolumeOptions& options, Device& device,
                               VolumeEstimateStats* stats) {
  return device_call(device, "curvature",
                     [&] { return run(mesh, volume, isovalue, options, device, stats); });
}

}  // namespace isocurv::curvature
