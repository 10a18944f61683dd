// The volume estimator on an OpenCL device: the driver over the passes of
// detail/volume_passes.h (see volume_estimate.h; the reference is volume_reference.cpp).
#include "curvature/volume_estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>

#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "curvature/detail/volume_passes.h"
#include "curvature/detail/volume_setup.h"

namespace isocurv::curvature {
namespace {

using Clock = StepClock;

// One evaluation at setup.sigma for `positions` (detail::VolumeEvaluate); `s` is locked.
detail::VolumeEvaluation evaluate(const Positions& positions, const volume::Volume& volume,
                                  const detail::VolumeSetup& setup, float isovalue, float ao_scale,
                                  Device& device, detail::VolumeSession& s, detail::RawPool& raw) {
  detail::VolumeEvaluation e;
  if (positions.empty()) return e;
  detail::Staging st;                 // read by queued copies until the queue drains ...
  const DrainOnUnwind drain(device);  // ... which an error makes sure of before st goes
  Clock::time_point t = Clock::now();
  detail::plan_pass(positions, setup, st);
  e.steps.plan = lap(t);
  cl::Buffer& pool = detail::gather_pass(volume, raw, device, s, st);
  e.steps.gather = lap(t);
  cl::Buffer& table = detail::smooth_pass(setup, volume, pool, device, s, st);
  cl::Buffer& blocks = detail::pad_pass(volume, device, s, st);
  device.queue().finish();
  e.steps.smooth = lap(t);
  detail::evaluate_pass(positions, setup, isovalue, ao_scale, volume, blocks, table, device, s, st);
  detail::read_back_pass(positions.size(), setup, device, s, e);
  device.queue().finish();
  e.steps.vertices = lap(t);
  e.bricks = 0;
  for (const volume::BrickSet& stage : st.plan.stages) e.bricks += stage.bricks.size();
  return e;
}

CurvatureField run(const Mesh& mesh, const volume::Volume& volume, float isovalue,
                   const VolumeOptions& options, Device& device, VolumeEstimateStats* stats) {
  const detail::VolumeSetup setup = detail::volume_setup(mesh, volume, options);
  const float ao_scale = options.ao_scale;
  const SurfacePiece* piece = options.piece;
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
  detail::VolumeSession& s = detail::volume_session(device);
  std::lock_guard<std::mutex> lock(s.mutex);
  double prefill_ms = 0;
  detail::ScaleLadder ladder;
  VertexCorners corners;  // built once: the cut and the areas both need them
  build_vertex_corners(mesh, corners);
  detail::RawPool raw;                // read by queued copies until the queue drains ...
  const DrainOnUnwind drain(device);  // ... which an error makes sure of before raw goes
  if (adaptive) {
    // Every rung reads a subset of the largest scale's raw bricks: gather and upload those once.
    Clock::time_point t = Clock::now();
    const detail::VolumeSetup widest = detail::with_sigma(setup, adaptive->hi);
    detail::prefill_pass(volume::plan_smoothing(setup.frame, mesh.positions,
                                                detail::spline_reach(widest), adaptive->hi),
                         volume, raw, device, s);
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
  if (setup.point == VolumePoint::vertex)
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
