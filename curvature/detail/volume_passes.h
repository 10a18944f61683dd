#pragma once
// The volume estimator's device passes (curvature/volume_estimate.h), in the order the driver in
// volume_estimate.cpp runs them for each scale: plan (the bricks the vertices read), gather (their
// raw samples, uploaded once per estimate), smooth (the separable prefilter, three passes), pad
// (the smoothed bricks with the B-spline's apron), evaluate (one work item per vertex) and read
// back. Each pass reads and writes the evaluation's Staging; the kernels are
// curvature/volume_kernels.cl, their parameter layout curvature/detail/volume_layout.h.
// Threading: a pass runs with its Session locked (one estimate at a time per device).
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include "core/cl_device.h"
#include "core/cl_scratch.h"
#include "curvature/detail/volume_layout.h"
#include "curvature/detail/volume_setup.h"
#include "volume/prefilter.h"
#include "volume/volume.h"

namespace isocurv::curvature::detail {

/// What the volume estimator keeps on one device between calls (Device::state): the kernels and
/// the buffers, reused while large enough.
struct VolumeSession {
  /// The buffers' slots in `buffers`.
  enum Slot : std::size_t {
    kPositions,
    kPool0,  ///< kPool0 + n: stage n's samples (volume::SmoothingPlan::stages)
    kPool1,
    kPool2,
    kPool3,
    kTable0,  ///< kTable0 + n: stage n's brick table
    kTable1,
    kTable2,
    kTable3,
    kBricks1,  ///< kBricks1 + a: the output bricks of the pass along axis a
    kBricks2,
    kBricks3,
    kTaps0,  ///< kTaps0 + a: the prefilter along axis a
    kTaps1,
    kTaps2,
    kBlocks,  ///< the smoothed samples in padded blocks (pad_pass)
    kParams,
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
  explicit VolumeSession(Device& device);
  /// The buffer of `slot`, at least `bytes` long (16 at least).
  cl::Buffer& get(Slot slot, std::size_t bytes);
  std::mutex mutex;  ///< one estimate at a time per device (kernel arguments are shared state)
  ScratchBuffers buffers;
  cl::Kernel kernel, smooth, pad;
};

/// The session of `device`, made (and its program built) on first use.
VolumeSession& volume_session(Device& device);

/// The raw samples of one pyramid level (volume/pyramid.h) for one estimate, on the host,
/// gathered once for the level's widest plan (every vertex at the largest scale the estimate
/// reads from that level), so every plan of that level's evaluations reads a subset of its bricks.
/// Gathering them again per evaluation was the largest part of the per-vertex choice's cost (the
/// gyroid's 628k vertices: 773 of 2585 ms). Lives until the estimate's queue has drained.
struct RawPool {
  std::optional<volume::SmoothingPlan> widest;
  std::vector<float> samples;  ///< 512 per brick of widest's stage 0, in its order
};

/// One evaluation's plan and the host arrays its queued copies read: they live until the
/// evaluation's queue has drained.
struct Staging {
  volume::SmoothingPlan plan;
  cl_int4 dims{};                    ///< the plan's region, in bricks
  openvdb::Coord first;              ///< the region's first voxel
  std::vector<std::int32_t> table0;  ///< stage 0's bricks, numbered in the raw pool
  std::vector<cl_int4> bricks[3];    ///< each smoothing pass's output bricks
  std::vector<float> taps[3];        ///< each pass's taps, as smooth_axis spreads them
  VolumeParams params{};             ///< volume_curvature's parameter block
};

/// plan: the bricks `positions` need at setup.sigma, into `st`.
void plan_pass(const Positions& positions, const VolumeSetup& setup, Staging& st);

/// gather: the raw samples' device buffer (uploaded by prefill_pass or upload_raw_pass from
/// `raw`) and st.table0 (stage 0's table remapped into the pool). Throws isocurv::Error when a
/// brick of st.plan is not in raw's widest plan (which would read the background silently).
cl::Buffer& gather_pass(const RawPool& raw, VolumeSession& s, Staging& st);

/// smooth: the prefilter's three passes (along x from stage 0 into stage 1, along y, along z)
/// from `pool`; returns stage 3's table.
cl::Buffer& smooth_pass(const VolumeSetup& setup, const volume::Volume& volume, cl::Buffer& pool,
                        Device& device, VolumeSession& s, Staging& st);

/// pad: stage 3's bricks in padded blocks (PADDED^3 voxels each, volume_layout.h).
cl::Buffer& pad_pass(const volume::Volume& volume, Device& device, VolumeSession& s, Staging& st);

/// evaluate: volume_curvature over `positions`, reading `blocks` through stage 3's `table`.
void evaluate_pass(const Positions& positions, const VolumeSetup& setup, float isovalue,
                   float ao_scale, const volume::Volume& volume, cl::Buffer& blocks,
                   cl::Buffer& table, Device& device, VolumeSession& s, Staging& st);

/// read back: the kernel's outputs into e.field and e.raw (non-blocking: valid once the queue
/// has drained).
void read_back_pass(std::size_t vertices, const VolumeSetup& setup, Device& device,
                    VolumeSession& s, VolumeEvaluation& e);

/// Gathers `widest`'s raw samples from `grid` (a pyramid level's, holding them) into `raw`
/// and uploads them.
void prefill_pass(const volume::SmoothingPlan& widest, const openvdb::FloatGrid& grid, RawPool& raw,
                  Device& device, VolumeSession& s);
/// Uploads `raw`'s samples again (the estimate moved to another level and back).
void upload_raw_pass(const RawPool& raw, Device& device, VolumeSession& s);

}  // namespace isocurv::curvature::detail
