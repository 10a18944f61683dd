// The volume estimator's specification, volume_estimate_reference: the device path's passes in
// double precision on the host (the steps both share are in detail/volume_setup.cpp).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/mesh_measures.h"
#include "curvature/adaptive_scale.h"
#include "curvature/derived.h"
#include "curvature/detail/local_geometry.h"
#include "curvature/detail/volume_setup.h"
#include "curvature/implicit_curvature.h"
#include "curvature/input.h"
#include "curvature/mesh_areas.h"
#include "curvature/volume_estimate.h"
#include "volume/gaussian_jet.h"
#include "volume/gradient_normals.h"
#include "volume/prefilter.h"
#include "volume/pyramid.h"
#include "volume/spline_jet.h"

namespace isocurv::curvature {

namespace {

/// The smoothing's shrinkage at a point of the smoothed isosurface of mean curvature h:
/// sigma2 h (1 - kSurfaceY1 y + kSurfaceY2 y^2), y = sigma2 h^2, the factor at least 1/2
/// (volume_estimate.h).
double shrinkage(double h, double sigma2) {
  const double y = sigma2 * h * h;
  return sigma2 * h * std::max(1 - kSurfaceY1 * y + kSurfaceY2 * y * y, 0.5);
}

/// The curvature of the parallel surface at distance e = shrinkage(H) outward
/// (volume_estimate.h: smoothing moves the isosurface inward by about sigma^2 H): k_i / (1 + e k_i),
/// each factor kept at 0.1 or more; directions and dcurv unchanged.
void shrinkage_corrected(PointCurvature& c, double e) {
  c.k1 /= std::max(1 + e * c.k1, 0.1);
  c.k2 /= std::max(1 + e * c.k2, 0.1);
}

}  // namespace

namespace {

detail::VolumeEvaluation evaluate_reference(const Positions& positions, volume::Pyramid& pyramid,
                                            const detail::VolumeSetup& s, float isovalue,
                                            float ao_scale) {
  const std::size_t nv = positions.size();
  detail::VolumeEvaluation e;
  if (nv == 0) return e;
  // The pyramid level that holds the scale, its bricks built as the plan reads them.
  const int k = pyramid.level_for(s.sigma);
  const detail::VolumeSetup at = detail::on_level(s, pyramid, k);
  const volume::SmoothingPlan plan = detail::plan_of(positions, at);
  pyramid.build(k, plan.stages[0].bricks);
  const volume::SmoothedSamples smoothed = volume::smooth_reference(*pyramid.level(k).grid, plan);
  CurvatureField& out = e.field;
  out.normals.resize(nv), out.k1.resize(nv), out.k2.resize(nv), out.dir1.resize(nv);
  out.dir2.resize(nv), out.H.resize(nv), out.K.resize(nv), out.dcurv.resize(nv);
  out.shape_index.resize(nv), out.curvedness.resize(nv), out.ao.resize(nv);
  if (s.point == VolumePoint::surface) out.surface_points.resize(nv);
  e.raw = {std::vector<float>(nv, 0.0f), std::vector<float>(nv, 0.0f)};
  detail::RawVertex& raw = e.raw;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f& p = positions[i];
      const openvdb::Vec3d x0(p[0], p[1], p[2]);
      // The level set of the smoothed field through the evaluation point (volume_estimate.h):
      // the vertex itself, or (surface) where its gradient line meets the smoothed isosurface.
      openvdb::Vec3d x = x0;
      double t = 0;
      if (s.point != VolumePoint::vertex) {
        const volume::Jet j0 = volume::spline_jet(smoothed, x0, 1);
        const openvdb::Vec3d g0(j0.gradient[0], j0.gradient[1], j0.gradient[2]);
        const double g0len = g0.length();
        if (g0len > 0 && std::isfinite(g0len)) {
          const openvdb::Vec3d d = g0 / g0len;
          volume::Jet j = j0;
          for (int step = 0; step < kNewtonSteps; ++step) {
            if (step > 0) j = volume::spline_jet(smoothed, x0 + t * d, 1);
            const double slope =
                j.gradient[0] * d[0] + j.gradient[1] * d[1] + j.gradient[2] * d[2];
            if (!(std::abs(slope) > 0)) break;
            t = std::clamp(t - (j.value - isovalue) / slope, -s.max_shift(), s.max_shift());
          }
          x = x0 + t * d;
        }
      }
      const volume::Jet jet = volume::spline_jet(smoothed, x, 3);
      PointCurvature c = implicit_curvature(jet, s.inside);
      const double e_shrink = shrinkage(0.5 * (c.k1 + c.k2), s.sigma * s.sigma);
      if (s.point == VolumePoint::surface) {
        // The surface point (CurvatureField::surface_points): on the parallel surface e_shrink
        // further out; the vertex where the gradient vanished.
        openvdb::Vec3d surface = x0;
        if (c.gradient_norm > 0 && std::isfinite(c.gradient_norm))
          surface = x + e_shrink * openvdb::Vec3d(c.normal.x(), c.normal.y(), c.normal.z());
        out.surface_points[i] = {float(surface[0]), float(surface[1]), float(surface[2])};
      }
      raw.shift[i] = c.gradient_norm > 0 && std::isfinite(c.gradient_norm)
                         ? float((jet.value - isovalue) / c.gradient_norm - t)
                         : std::numeric_limits<float>::infinity();
      if (s.point == VolumePoint::surface) {
        // Past kMinCorrection the parallel surface is not what the smoothing moved: the scale
        // does not fit (volume_estimate.h).
        if (std::min(1 + e_shrink * c.k1, 1 + e_shrink * c.k2) < kMinCorrection)
          raw.shift[i] = std::numeric_limits<float>::infinity();
        shrinkage_corrected(c, e_shrink);
      }
      raw.gradient_norm[i] = float(c.gradient_norm);
      out.normals[i] = detail::to_f3(c.normal);
      out.k1[i] = float(c.k1), out.k2[i] = float(c.k2);
      out.dir1[i] = detail::to_f3(c.dir1), out.dir2[i] = detail::to_f3(c.dir2);
      out.H[i] = float((c.k1 + c.k2) / 2), out.K[i] = float(c.k1 * c.k2);
      out.dcurv[i] = {float(c.dcurv[0]), float(c.dcurv[1]), float(c.dcurv[2]), float(c.dcurv[3])};
      out.shape_index[i] = float(shape_index(c.k1, c.k2));
      out.curvedness[i] = float(curvedness(c.k1, c.k2));
      out.ao[i] = float(ambient_occlusion(c.k1, c.k2, double(ao_scale)));
    }
  });
  return e;
}

}  // namespace

CurvatureField volume_estimate_reference(const Mesh& mesh, const volume::Volume& volume,
                                         float isovalue, const VolumeOptions& options,
                                         VolumeEstimateStats* stats) {
  const detail::VolumeSetup setup = detail::volume_setup(mesh, volume, options);
  const float ao_scale = options.ao_scale;
  const std::optional<detail::AdaptiveScale> adaptive = detail::adaptive_of(options, setup, volume);
  volume::PyramidLease lease(volume);  // kept between estimates on this volume
  volume::Pyramid& pyramid = *lease;
  const std::size_t kept_bricks = pyramid.built_bricks();
  detail::ScaleLadder ladder;
  VertexCorners corners;  // built once: the cut and the areas both need them
  build_vertex_corners(mesh, corners);
  detail::VolumeEvaluation e = detail::evaluate_with_finer_scales(
      mesh, corners, setup, options.finer_scales,
      [&](const Positions& positions, const detail::VolumeSetup& s) {
        return evaluate_reference(positions, pyramid, s, isovalue, ao_scale);
      },
      ladder, adaptive ? &*adaptive : nullptr);
  const std::size_t unreliable = detail::finish_volume_field(
      mesh, corners, e.raw, ladder, options.finer_scales, ao_scale, e.field, options.piece);
  if (setup.point == VolumePoint::vertex)
    e.field.surface_points = edge_surface_points(mesh, volume, e.field);
  if (stats)
    *stats = VolumeEstimateStats{unreliable, 0, ladder.refined, detail::count_of(ladder.outside),
                                 ladder.blur, {}, kept_bricks};
  return std::move(e.field);
}

}  // namespace isocurv::curvature
