// The volume estimator's device passes (volume_passes.h).
#include "curvature/detail/volume_passes.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>

#include "core/cl_launch.h"
#include "core/error.h"
#include "curvature/derived.h"
#include "curvature/detail/math_options.h"
#include "curvature/tolerances.h"

namespace isocurv::kernels {
extern const char* const curvature_math_cl;
extern const char* const volume_kernels_cl;
extern const char* const volume_layout_h;
}  // namespace isocurv::kernels

namespace isocurv::curvature::detail {

// The C header's layout as the host sees it: the kernel reads VolumeParams from one buffer.
static_assert(sizeof(VolumeParams) == 157 * sizeof(float),
              "VolumeParams: 157 packed 4-byte fields");
static_assert(offsetof(VolumeParams, origin) == 9 * sizeof(float));
static_assert(offsetof(VolumeParams, m2) == 12 * sizeof(float));
static_assert(offsetof(VolumeParams, m3) == 48 * sizeof(float));
static_assert(offsetof(VolumeParams, first) == 148 * sizeof(float));
static_assert(offsetof(VolumeParams, isovalue) == 151 * sizeof(float));
static_assert(offsetof(VolumeParams, surface) == 154 * sizeof(float) && sizeof(int) == 4);
static_assert(offsetof(VolumeParams, sigma2) == 156 * sizeof(float));
static_assert(BRICK_VOXELS == VOLUME_BRICK_EDGE * VOLUME_BRICK_EDGE * VOLUME_BRICK_EDGE);
static_assert(BRICK_ROWS * VOLUME_BRICK_EDGE == BRICK_VOXELS);
static_assert(SPLINE_TAPS == 5, "the quartic B-spline (volume/spline_jet.h)");

namespace {

constexpr std::size_t kGroup = 64;  // work-group size of the launches (core/cl_launch.h)

// The tuning constants the kernels share with the reference, from their C++ definitions.
std::string build_options() {
  char buf[200];
  std::snprintf(buf, sizeof buf, " -DNEWTON_STEPS=%d -DSURFACE_Y1=%.9ef -DSURFACE_Y2=%.9ef -DMIN_CORRECTION=%.9ef",
                kNewtonSteps, kSurfaceY1, kSurfaceY2, kMinCorrection);
  return math_build_options() + buf;
}

template <class T, class A>
cl::Buffer& upload(cl::CommandQueue& q, VolumeSession& s, VolumeSession::Slot slot,
                   const std::vector<T, A>& v) {
  cl::Buffer& b = s.get(slot, v.size() * sizeof(T));
  if (!v.empty()) q.enqueueWriteBuffer(b, CL_FALSE, 0, v.size() * sizeof(T), v.data());
  return b;
}

template <class T>
void download(cl::CommandQueue& q, cl::Buffer& b, std::vector<T>& v, std::size_t n) {
  v.resize(n);
  if (n) q.enqueueReadBuffer(b, CL_FALSE, 0, n * sizeof(T), v.data());
}

// The maps from the distinct index-space derivatives of orders 2 and 3 to the world-space
// Hessian and third derivatives (VolumeParams::m2, m3): m2[e][f] = sum over the ordered index
// pairs (a, b) of f's orders of B(a, k) B(b, l) for the world pair e = (k, l); m3 likewise over
// ordered triples.
void world_maps(const openvdb::Mat3d& B, VolumeParams& p) {
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
  for (int e = 0; e < 6; ++e)
    for (int f = 0; f < 6; ++f) p.m2[e][f] = float(m2[e][f]);
  for (int e = 0; e < 10; ++e)
    for (int f = 0; f < 10; ++f) p.m3[e][f] = float(m3[e][f]);
}

}  // namespace

VolumeSession::VolumeSession(Device& device) : buffers(device, kSlots) {
  static const std::string source = std::string(kernels::volume_layout_h) + "\n" +
                                    kernels::curvature_math_cl + "\n" + kernels::volume_kernels_cl;
  cl::Program& program = device.program("volume_curvature", source.c_str(), build_options());
  kernel = cl::Kernel(program, "volume_curvature");
  smooth = cl::Kernel(program, "smooth_axis");
  pad = cl::Kernel(program, "pad_bricks");
}

cl::Buffer& VolumeSession::get(Slot slot, std::size_t bytes) {
  return buffers.get(slot, std::max<std::size_t>(bytes, 16));
}

VolumeSession& volume_session(Device& device) {
  static std::mutex creating;  // Device::state is for one thread at a time
  std::lock_guard<std::mutex> lock(creating);
  return device.state<VolumeSession>();
}

void plan_pass(const Positions& positions, const VolumeSetup& setup, Staging& st) {
  st.plan = plan_of(positions, setup);
  const volume::SmoothingPlan& plan = st.plan;
  st.dims = {{plan.dims[0], plan.dims[1], plan.dims[2], 0}};
  st.first = openvdb::Coord(plan.origin[0] * 8, plan.origin[1] * 8, plan.origin[2] * 8);
}

void upload_raw_pass(const RawPool& raw, Device& device, VolumeSession& s) {
  cl::Buffer& pool = s.get(VolumeSession::kPool0, raw.samples.size() * sizeof(float));
  if (!raw.samples.empty())  // `raw` outlives the estimate's queue
    device.queue().enqueueWriteBuffer(pool, CL_FALSE, 0, raw.samples.size() * sizeof(float),
                                      raw.samples.data());
}

void prefill_pass(const volume::SmoothingPlan& widest, const openvdb::FloatGrid& grid, RawPool& raw,
                  Device& device, VolumeSession& s) {
  raw.widest = widest;
  raw.samples.clear();
  volume::gather_bricks(grid, widest.frame, widest.stages[0].bricks, raw.samples);
  upload_raw_pass(raw, device, s);
}

cl::Buffer& gather_pass(const RawPool& raw, VolumeSession& s, Staging& st) {
  if (!raw.widest) throw Error("curvature: an evaluation before its level's raw samples");
  // The same size as uploaded: kept as it is.
  cl::Buffer& pool = s.get(VolumeSession::kPool0, raw.samples.size() * sizeof(float));
  const volume::SmoothingPlan& w = *raw.widest;
  const volume::BrickSet& set = st.plan.stages[0];
  st.table0.assign(set.table.size(), -1);
  for (const openvdb::Coord& b : set.bricks) {
    const std::int32_t slot = w.in_region(b) ? w.stages[0].table[w.cell(b)] : -1;
    if (slot < 0) throw Error("curvature: a smoothing plan reaches past the estimate's widest one");
    st.table0[st.plan.cell(b)] = slot;
  }
  return pool;
}

cl::Buffer& smooth_pass(const VolumeSetup& setup, const volume::Volume& volume, cl::Buffer& pool,
                        Device& device, VolumeSession& s, Staging& st) {
  using S = VolumeSession;
  const volume::SmoothingPlan& plan = st.plan;
  const volume::GridFrame& fr = setup.frame;
  const cl_float background = volume.grid->background();
  cl::CommandQueue& q = device.queue();
  upload(q, s, S::kTable0, st.table0);
  for (int n = 1; n < 4; ++n) upload(q, s, S::Slot(S::kTable0 + n), plan.stages[n].table);
  for (int a = 0; a < 3; ++a) {
    const volume::BrickSet& out = plan.stages[a + 1];
    st.bricks[a].clear();
    for (const openvdb::Coord& b : out.bricks) {
      const openvdb::Coord r = b - plan.origin;
      st.bricks[a].push_back({{r[0], r[1], r[2], 0}});
    }
    // smooth_axis's `spread`: the taps reversed with 7 zeros either side.
    const int radius = plan.taps[a].radius;
    st.taps[a].assign(2 * radius + 15, 0.0f);
    for (int k = 0; k <= 2 * radius; ++k) st.taps[a][2 * radius + 7 - k] = float(plan.taps[a].w[k]);
    cl::Buffer& from = a == 0 ? pool
                              : s.get(S::Slot(S::kPool0 + a),
                                      plan.stages[a].bricks.size() * BRICK_VOXELS * sizeof(float));
    cl::Buffer& to =
        s.get(S::Slot(S::kPool0 + a + 1), out.bricks.size() * BRICK_VOXELS * sizeof(float));
    cl::Buffer& list = upload(q, s, S::Slot(S::kBricks1 + a), st.bricks[a]);
    cl::Buffer& weights = upload(q, s, S::Slot(S::kTaps0 + a), st.taps[a]);
    set_args(s.smooth, from, s.get(S::Slot(S::kTable0 + a), 0), st.dims, background, list,
             cl_uint(out.bricks.size()), to, cl_int(a), cl_int(fr.clamp),
             cl_int(fr.lo[a] - st.first[a]), cl_int(fr.hi[a] - st.first[a]), weights,
             cl_int(plan.taps[a].radius));
    launch(q, s.smooth, out.bricks.size() * BRICK_ROWS, kGroup);
  }
  return s.get(S::kTable3, 0);
}

cl::Buffer& pad_pass(const volume::Volume& volume, Device& device, VolumeSession& s, Staging& st) {
  using S = VolumeSession;
  const std::size_t n3 = st.plan.stages[3].bricks.size();
  cl::Buffer& blocks = s.get(S::kBlocks, n3 * PADDED_VOXELS * sizeof(float));
  set_args(s.pad, s.get(S::kPool3, 0), s.get(S::kTable3, 0), st.dims,
           cl_float(volume.grid->background()), s.get(S::kBricks3, 0), cl_uint(n3), blocks);
  launch(device.queue(), s.pad, n3 * PADDED * PADDED, kGroup);
  return blocks;
}

void evaluate_pass(const Positions& positions, const VolumeSetup& setup, float isovalue,
                   float ao_scale, const volume::Volume& volume, cl::Buffer& blocks,
                   cl::Buffer& table, Device& device, VolumeSession& s, Staging& st) {
  using S = VolumeSession;
  const std::size_t nv = positions.size();
  const volume::GridFrame& fr = setup.frame;
  // The kernel measures positions from a fixed anchor, the brick holding the volume's first
  // voxel, not from the plan's first brick: the float rounding of a vertex's index position then
  // does not depend on which vertices share the plan, so a piece of a distributed surface
  // (core/surface_piece.h) gets the single process's values to the bit. The region's first
  // voxel less the anchor is a whole number, subtracted exactly.
  const openvdb::Coord anchor(fr.lo[0] & ~7, fr.lo[1] & ~7, fr.lo[2] & ~7);
  const openvdb::Vec3d at = fr.to_world(openvdb::Vec3d(anchor.asVec3d()));
  VolumeParams& p = st.params;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) p.b[3 * r + c] = float(fr.B(r, c));
  for (int a = 0; a < 3; ++a) p.origin[a] = float(at[a]);
  world_maps(fr.B, p);
  for (int a = 0; a < 3; ++a) p.first[a] = float(st.first[a] - anchor[a]);
  p.isovalue = isovalue;
  p.sign = volume.inside == volume::Inside::Above ? -1.0f : 1.0f;
  p.ao_scale = ao_scale;
  p.surface = setup.point == VolumePoint::surface;
  p.max_shift = float(setup.max_shift());
  p.sigma2 = float(setup.sigma * setup.sigma);

  cl::CommandQueue& q = device.queue();
  cl::Buffer& pos = upload(q, s, S::kPositions, positions);
  cl::Buffer& params = s.get(S::kParams, sizeof(VolumeParams));
  q.enqueueWriteBuffer(params, CL_FALSE, 0, sizeof(VolumeParams), &st.params);
  auto floats = [&](S::Slot slot) -> cl::Buffer& { return s.get(slot, nv * sizeof(float)); };
  auto triples = [&](S::Slot slot) -> cl::Buffer& { return s.get(slot, nv * sizeof(Vec3f)); };
  set_args(s.kernel, pos, cl_uint(nv), blocks, table, st.dims, params, triples(S::kNormals),
           floats(S::kK1), floats(S::kK2), triples(S::kDir1), triples(S::kDir2), floats(S::kH),
           floats(S::kK), s.get(S::kDcurv, nv * sizeof(cl_float4)), floats(S::kShape),
           floats(S::kCurved), floats(S::kAo), floats(S::kGradientNorm), floats(S::kShift),
           triples(S::kSurface));
  launch(q, s.kernel, nv, kGroup);
}

void read_back_pass(std::size_t nv, const VolumeSetup& setup, Device& device, VolumeSession& s,
                    VolumeEvaluation& e) {
  using S = VolumeSession;
  cl::CommandQueue& q = device.queue();
  CurvatureField& out = e.field;
  download(q, s.get(S::kNormals, 0), out.normals, nv);
  download(q, s.get(S::kK1, 0), out.k1, nv);
  download(q, s.get(S::kK2, 0), out.k2, nv);
  download(q, s.get(S::kDir1, 0), out.dir1, nv);
  download(q, s.get(S::kDir2, 0), out.dir2, nv);
  download(q, s.get(S::kH, 0), out.H, nv);
  download(q, s.get(S::kK, 0), out.K, nv);
  download(q, s.get(S::kDcurv, 0), out.dcurv, nv);
  download(q, s.get(S::kShape, 0), out.shape_index, nv);
  download(q, s.get(S::kCurved, 0), out.curvedness, nv);
  download(q, s.get(S::kAo, 0), out.ao, nv);
  download(q, s.get(S::kGradientNorm, 0), e.raw.gradient_norm, nv);
  download(q, s.get(S::kShift, 0), e.raw.shift, nv);
  if (setup.point == VolumePoint::surface)
    download(q, s.get(S::kSurface, 0), out.surface_points, nv);
}

}  // namespace isocurv::curvature::detail
