// The volume estimator on an OpenCL device: the driver over the passes of
// detail/volume_passes.h (see volume_estimate.h; the reference is volume_reference.cpp).
#include "curvature/volume_estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "core/device_call.h"
#include "core/error.h"
#include "core/lap.h"
#include "curvature/detail/volume_passes.h"
#include "curvature/detail/volume_setup.h"
#include "volume/pyramid.h"

namespace isocurv::curvature {
namespace {

using Clock = StepClock;

// The pyramid levels' raw samples of one estimate (detail::RawPool per level), gathered once
// per level for every vertex at the largest scale the estimate reads from it, and which level's
// are on the device.
struct RawPools {
  const Positions* positions = nullptr;  ///< the whole surface's vertices
  double largest = 0;                    ///< the estimate's largest scale, world units
  std::map<int, detail::RawPool> levels;
  int uploaded = -1;
};

// One evaluation at setup.sigma for `positions` (detail::VolumeEvaluate), on the pyramid level
// that holds the scale; `s` is locked.
detail::VolumeEvaluation evaluate(const Positions& positions, const volume::Volume& volume,
                                  volume::Pyramid& pyramid, const detail::VolumeSetup& setup,
                                  float isovalue, float ao_scale, Device& device,
                                  detail::VolumeSession& s, RawPools& raws) {
  detail::VolumeEvaluation e;
  if (positions.empty()) return e;
  detail::Staging st;                 // read by queued copies until the queue drains ...
  const DrainOnUnwind drain(device);  // ... which an error makes sure of before st goes
  Clock::time_point t = Clock::now();
  const int k = pyramid.level_for(setup.sigma);
  const detail::VolumeSetup at = detail::on_level(setup, pyramid, k);
  detail::plan_pass(positions, at, st);
  e.steps.plan = lap(t);
  detail::RawPool& raw = raws.levels[k];
  if (!raw.widest) {
    // Every vertex at the largest scale this level serves in this estimate.
    const double top =
        std::max(setup.sigma, std::min(raws.largest, pyramid.upper_scale(k) * (1 - 1e-9)));
    const volume::SmoothingPlan widest =
        detail::plan_of(*raws.positions, detail::with_sigma(at, top));
    pyramid.build(k, widest.stages[0].bricks);
    detail::prefill_pass(widest, *pyramid.level(k).grid, raw, device, s);
    raws.uploaded = k;
  } else if (raws.uploaded != k) {
    detail::upload_raw_pass(raw, device, s);
    raws.uploaded = k;
  }
  cl::Buffer& pool = detail::gather_pass(raw, s, st);
  e.steps.gather = lap(t);
  cl::Buffer& table = detail::smooth_pass(at, volume, pool, device, s, st);
  cl::Buffer& blocks = detail::pad_pass(volume, device, s, st);
  device.queue().finish();
  e.steps.smooth = lap(t);
  detail::evaluate_pass(positions, at, isovalue, ao_scale, volume, blocks, table, device, s, st);
  detail::read_back_pass(positions.size(), at, device, s, e);
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
  detail::ScaleLadder ladder;
  VertexCorners corners;  // built once: the cut and the areas both need them
  build_vertex_corners(mesh, corners);
  volume::PyramidLease lease(volume);  // kept between estimates on this volume
  volume::Pyramid& pyramid = *lease;
  const std::size_t kept_bricks = pyramid.built_bricks();
  RawPools raws;                      // read by queued copies until the queue drains ...
  const DrainOnUnwind drain(device);  // ... which an error makes sure of before raws go
  raws.positions = &mesh.positions;
  raws.largest = adaptive ? std::max(adaptive->hi, setup.sigma) : setup.sigma;
  detail::VolumeEvaluation e = detail::evaluate_with_finer_scales(
      mesh, corners, setup, options.finer_scales,
      [&](const Positions& positions, const detail::VolumeSetup& at) {
        return evaluate(positions, volume, pyramid, at, isovalue, ao_scale, device, s, raws);
      },
      ladder, adaptive ? &*adaptive : nullptr);
  Clock::time_point t = Clock::now();
  const std::size_t unreliable = detail::finish_volume_field(
      mesh, corners, e.raw, ladder, options.finer_scales, ao_scale, e.field, piece);
  if (setup.point == VolumePoint::vertex)
    e.field.surface_points = edge_surface_points(mesh, volume, e.field);
  e.steps.finish = lap(t);
  if (stats)
    *stats = VolumeEstimateStats{unreliable, e.bricks, ladder.refined,
                                 detail::count_of(ladder.outside), ladder.blur, e.steps,
                                 kept_bricks};
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
