// The volume estimator's specification (volume_estimate_reference) and the steps the device path
// shares with it (detail/volume_setup.h).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/mesh_measures.h"
#include "curvature/derived.h"
#include "curvature/detail/volume_setup.h"
#include "curvature/implicit_curvature.h"
#include "curvature/input.h"
#include "curvature/mesh_areas.h"
#include "curvature/volume_estimate.h"
#include "volume/gradient_normals.h"
#include "volume/prefilter.h"
#include "volume/spline_jet.h"

namespace isocurv::curvature {
namespace detail {

VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume, double sigma) {
  check_input(mesh, Options{});
  if (!volume.grid) throw Error("curvature: the volume estimator needs a volume");
  VolumeSetup s;
  s.frame = volume::grid_frame(volume);
  s.voxel = std::max({s.frame.spacing[0], s.frame.spacing[1], s.frame.spacing[2]});
  const double finest = std::min({s.frame.spacing[0], s.frame.spacing[1], s.frame.spacing[2]});
  if (!(sigma > 0) || !std::isfinite(sigma))
    throw Error("curvature: the scale must be a positive finite number (world units), not " +
                std::to_string(sigma));
  if (!volume.domain.empty()) {
    const openvdb::Coord dim = volume.domain.dim();
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, dim[a] * s.frame.spacing[a]);
    if (sigma > extent)
      throw Error(volume.path, "scale " + std::to_string(sigma) + " is larger than the volume (" +
                                   std::to_string(extent) + " world units across)");
  }
  if (sigma / finest > volume::kMaxDeviation)
    throw Error(volume.path, "scale " + std::to_string(sigma) + " is " +
                                 std::to_string(sigma / finest) +
                                 " voxels along the finest axis; at most " +
                                 std::to_string(int(volume::kMaxDeviation)) + " are supported");
  if (sigma / s.voxel < volume::kMinScaleVoxels)
    throw Error(volume.path, "scale " + std::to_string(sigma) + " is " +
                                 std::to_string(sigma / s.voxel) +
                                 " voxels along the coarsest axis; at least " +
                                 std::to_string(volume::kMinScaleVoxels) +
                                 " are supported (the reconstruction's B-spline alone smooths "
                                 "by 0.645 voxel)");
  s.sigma = sigma;
  s.max_shift = kMaxShiftVoxels * s.voxel;
  s.inside = volume.inside;
  return s;
}

openvdb::Vec3d spline_reach(const VolumeSetup& setup) {
  openvdb::Vec3d reach;
  for (int a = 0; a < 3; ++a) reach[a] = setup.max_shift / setup.frame.spacing[a] + 1;
  return reach;
}

std::size_t finish_volume_field(const Mesh& mesh, const RawVertex& raw, float ao_scale,
                                CurvatureField& field) {
  const std::size_t nv = mesh.positions.size();
  VertexCorners corners;
  build_vertex_corners(mesh, corners);
  field.area = mixed_vertex_areas(mesh, corners);
  field.boundary = boundary_vertices(mesh, corners);
  field.unreliable.assign(nv, 0);
  std::vector<float> lengths;
  lengths.reserve(nv);
  for (float g : raw.gradient_norm)
    if (g > 0) lengths.push_back(g);
  float weak_below = 0;
  if (!lengths.empty()) {
    auto mid = lengths.begin() + lengths.size() / 2;
    std::nth_element(lengths.begin(), mid, lengths.end());
    weak_below = float(volume::kWeakGradientFraction) * *mid;
  }
  std::vector<Vec3f> faces;
  std::size_t count = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    if (raw.gradient_norm[i] > weak_below && !raw.missed[i]) continue;
    if (faces.empty()) faces = area_weighted_normals(mesh);
    field.unreliable[i] = 1;
    ++count;
    const Vec3f a = faces[i];
    const double len = std::sqrt(double(a[0]) * a[0] + double(a[1]) * a[1] + double(a[2]) * a[2]);
    field.normals[i] =
        len > 0 ? Vec3f{float(a[0] / len), float(a[1] / len), float(a[2] / len)} : Vec3f{0, 0, 0};
    field.k1[i] = field.k2[i] = field.H[i] = field.K[i] = 0;
    field.dir1[i] = field.dir2[i] = Vec3f{0, 0, 0};
    field.dcurv[i] = {0, 0, 0, 0};
    field.shape_index[i] = shape_index(0.0f, 0.0f);
    field.curvedness[i] = 0;
    field.ao[i] = ambient_occlusion(0.0f, 0.0f, ao_scale);
  }
  return count;
}

VolumeEvaluation evaluate_with_finer_scales(const Mesh& mesh, VolumeSetup setup, bool finer_scales,
                                            const VolumeEvaluate& evaluate, std::size_t& refined) {
  refined = 0;
  VolumeEvaluation all = evaluate(mesh.positions, setup);
  CurvatureField& f = all.field;
  while (finer_scales && setup.sigma > setup.voxel) {
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < all.raw.missed.size(); ++i)
      if (all.raw.missed[i]) which.push_back(i);
    if (which.empty()) break;
    setup.sigma = std::max(setup.sigma / 2, setup.voxel);
    Positions positions(which.size());
    for (std::size_t j = 0; j < which.size(); ++j) positions[j] = mesh.positions[which[j]];
    const VolumeEvaluation finer = evaluate(positions, setup);
    all.bricks += finer.bricks;
    all.steps.plan += finer.steps.plan, all.steps.gather += finer.steps.gather;
    all.steps.smooth += finer.steps.smooth, all.steps.vertices += finer.steps.vertices;
    const CurvatureField& g = finer.field;
    for (std::size_t j = 0; j < which.size(); ++j) {
      if (finer.raw.missed[j]) continue;
      const std::size_t i = which[j];
      f.normals[i] = g.normals[j], f.k1[i] = g.k1[j], f.k2[i] = g.k2[j];
      f.dir1[i] = g.dir1[j], f.dir2[i] = g.dir2[j], f.H[i] = g.H[j], f.K[i] = g.K[j];
      f.dcurv[i] = g.dcurv[j], f.shape_index[i] = g.shape_index[j];
      f.curvedness[i] = g.curvedness[j], f.ao[i] = g.ao[j];
      all.raw.gradient_norm[i] = finer.raw.gradient_norm[j];
      all.raw.missed[i] = 0;
      ++refined;
    }
  }
  return all;
}

}  // namespace detail

namespace {

Vec3f to_f3(const Eigen::Vector3d& v) { return {float(v.x()), float(v.y()), float(v.z())}; }

/// The last Newton step along `d`, taken on the full jet's Taylor expansion: it moves the jet the
/// last few 1e-3 voxel onto the surface without another evaluation. Steps over
/// kMaxFinalStepVoxels are not taken (the surface was missed; the caller flags it).
volume::Jet final_step(const volume::Jet& jet, const openvdb::Vec3d& d, float isovalue,
                       double voxel) {
  const double slope = jet.gradient[0] * d[0] + jet.gradient[1] * d[1] + jet.gradient[2] * d[2];
  if (!(std::abs(slope) > 0)) return jet;
  const double t = -(jet.value - isovalue) / slope;
  if (!(std::abs(t) <= kMaxFinalStepVoxels * voxel)) return jet;
  return volume::shifted_jet(jet, t * d);
}

}  // namespace

namespace {

detail::VolumeEvaluation evaluate_reference(const Positions& positions,
                                            const openvdb::FloatGrid& grid,
                                            const detail::VolumeSetup& s, float isovalue,
                                            float ao_scale) {
  const std::size_t nv = positions.size();
  detail::VolumeEvaluation e;
  if (nv == 0) return e;
  const volume::SmoothingPlan plan =
      volume::plan_smoothing(s.frame, positions, detail::spline_reach(s), s.sigma);
  const volume::SmoothedSamples smoothed = volume::smooth_reference(grid, plan);
  CurvatureField& out = e.field;
  out.normals.resize(nv), out.k1.resize(nv), out.k2.resize(nv), out.dir1.resize(nv);
  out.dir2.resize(nv), out.H.resize(nv), out.K.resize(nv), out.dcurv.resize(nv);
  out.shape_index.resize(nv), out.curvedness.resize(nv), out.ao.resize(nv);
  e.raw = {std::vector<float>(nv, 0.0f), std::vector<std::uint8_t>(nv, 0)};
  detail::RawVertex& raw = e.raw;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 256), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f& p = positions[i];
      const openvdb::Vec3d x0(p[0], p[1], p[2]);
      // The gradient line through the vertex, and Newton steps along it to F = isovalue.
      const volume::Jet j0 = volume::spline_jet(smoothed, x0, 1);
      const openvdb::Vec3d g0(j0.gradient[0], j0.gradient[1], j0.gradient[2]);
      const double g0len = g0.length();
      PointCurvature c;
      bool missed = true;
      if (g0len > 0 && std::isfinite(g0len)) {
        const openvdb::Vec3d d = g0 / g0len;
        double t = 0;
        volume::Jet j = j0;
        for (int step = 0; step < kNewtonSteps; ++step) {
          if (step > 0) j = volume::spline_jet(smoothed, x0 + t * d, 1);
          const double slope = j.gradient[0] * d[0] + j.gradient[1] * d[1] + j.gradient[2] * d[2];
          if (!(std::abs(slope) > 0)) break;
          t = std::clamp(t - (j.value - isovalue) / slope, -s.max_shift, s.max_shift);
        }
        const volume::Jet jet = volume::spline_jet(smoothed, x0 + t * d, 3);
        c = implicit_curvature(final_step(jet, d, isovalue, s.voxel), s.inside);
        missed = !(std::abs(jet.value - isovalue) <= kOnSurfaceVoxels * s.voxel * c.gradient_norm);
      }
      raw.gradient_norm[i] = float(c.gradient_norm);
      raw.missed[i] = missed;
      out.normals[i] = to_f3(c.normal);
      out.k1[i] = float(c.k1), out.k2[i] = float(c.k2);
      out.dir1[i] = to_f3(c.dir1), out.dir2[i] = to_f3(c.dir2);
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
                                         float isovalue, double sigma, float ao_scale,
                                         VolumeEstimateStats* stats, bool finer_scales) {
  const detail::VolumeSetup setup = detail::volume_setup(mesh, volume, sigma);
  if (!std::isfinite(ao_scale)) throw Error("curvature: ao_scale must be finite");
  const openvdb::FloatGrid& grid = *volume.grid;
  std::size_t refined = 0;
  detail::VolumeEvaluation e = detail::evaluate_with_finer_scales(
      mesh, setup, finer_scales,
      [&](const Positions& positions, const detail::VolumeSetup& s) {
        return evaluate_reference(positions, grid, s, isovalue, ao_scale);
      },
      refined);
  const std::size_t unreliable = detail::finish_volume_field(mesh, e.raw, ao_scale, e.field);
  if (stats) *stats = VolumeEstimateStats{unreliable, 0, refined, {}};
  return std::move(e.field);
}

}  // namespace isocurv::curvature
