// What the volume estimator's device path and its reference share (detail/volume_setup.h): the
// checked setup, the per-vertex choice of scale over evaluations, and the finishing pass.
#include "curvature/detail/volume_setup.h"

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
#include "curvature/auto_scale.h"
#include "curvature/derived.h"
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

VolumePoint resolved_point(VolumePoint point, const volume::Volume& volume) {
  if (point != VolumePoint::automatic) return point;
  return is_binary(volume) ? VolumePoint::surface : VolumePoint::vertex;
}

namespace detail {

VolumeSetup volume_setup(const Mesh& mesh, const volume::Volume& volume,
                         const VolumeOptions& options) {
  check_input(mesh, Options{});
  if (!volume.grid) throw Error("curvature: the volume estimator needs a volume");
  if (!std::isfinite(options.ao_scale)) throw Error("curvature: ao_scale must be finite");
  const double sigma = options.sigma;
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
  s.max_scale = volume::Pyramid(volume).max_scale();
  if (sigma > s.max_scale)
    throw Error(volume.path, "scale " + std::to_string(sigma) + " is " +
                                 std::to_string(sigma / finest) +
                                 " voxels along the finest axis; this volume supports at most " +
                                 std::to_string(s.max_scale / finest) +
                                 " (its thinnest side, smoothed, holds too few samples)");
  if (sigma / s.voxel < volume::kMinScaleVoxels)
    throw Error(volume.path, "scale " + std::to_string(sigma) + " is " +
                                 std::to_string(sigma / s.voxel) +
                                 " voxels along the coarsest axis; at least " +
                                 std::to_string(volume::kMinScaleVoxels) +
                                 " are supported (the reconstruction's B-spline alone smooths "
                                 "by 0.645 voxel)");
  s.sigma = sigma;
  const double mean_voxel = std::cbrt(s.frame.spacing[0] * s.frame.spacing[1] * s.frame.spacing[2]);
  s.floor = std::min(sigma,
                     std::max(kFloorVoxels * mean_voxel, 1.01 * volume::kMinScaleVoxels * s.voxel));
  s.inside = volume.inside;
  s.point = resolved_point(options.point, volume);
  return s;
}

volume::SmoothingPlan plan_of(const Positions& positions, const VolumeSetup& setup) {
  return volume::plan_smoothing(setup.frame, positions, spline_reach(setup), setup.sigma,
                                setup.own_variance);
}

openvdb::Vec3d spline_reach(const VolumeSetup& setup) {
  openvdb::Vec3d reach(0.5, 0.5, 0.5);
  if (setup.point == VolumePoint::surface)  // the Newton steps move up to max_shift()
    for (int a = 0; a < 3; ++a) reach[a] += setup.max_shift() / setup.frame.spacing[a];
  return reach;
}

std::optional<AdaptiveScale> adaptive_of(const VolumeOptions& options, const VolumeSetup& setup,
                                         const volume::Volume& volume) {
  if (!options.adaptive || !options.finer_scales) return std::nullopt;
  const std::array<double, 3> h = {setup.frame.spacing[0], setup.frame.spacing[1],
                                   setup.frame.spacing[2]};
  double hi = options.adaptive_max > 0 ? options.adaptive_max
                                       : kAdaptiveMaxVoxels * std::cbrt(h[0] * h[1] * h[2]);
  hi = std::min(hi, 0.999 * setup.max_scale);
  if (!volume.domain.empty()) {
    const openvdb::Coord dim = volume.domain.dim();
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, dim[a] * h[a]);
    hi = std::min(hi, extent);
  }
  if (!options.adaptive->staircase)
    hi = std::min(hi, kExtrapolation * kGreyPilots[1] * setup.sigma);
  if (!(hi > setup.sigma * (1 + 1e-6))) return std::nullopt;
  AdaptiveScale a{*options.adaptive, hi, options.piece, false, {}};
  if (!volume.domain.empty() && volume.grid) {
    const openvdb::Coord lo = volume.domain.min(), up = volume.domain.max();
    // The spread of the samples on the box's six faces (strided to at most 64 x 64 per face).
    openvdb::FloatGrid::ConstAccessor acc = volume.grid->getConstAccessor();
    double sum = 0, sum2 = 0, n = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        const int su = std::max(1, (up[u] - lo[u] + 1) / 64),
                  sv = std::max(1, (up[v] - lo[v] + 1) / 64);
        openvdb::Coord c;
        c[axis] = side ? up[axis] : lo[axis];
        for (c[u] = lo[u]; c[u] <= up[u]; c[u] += su)
          for (c[v] = lo[v]; c[v] <= up[v]; c[v] += sv) {
            const double x = acc.getValue(c);
            sum += x, sum2 += x * x, n += 1;
          }
      }
    const double mean = sum / n, spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
    const double range = volume.stats.max - volume.stats.min;
    a.border_varies = spread > kFlatBorderNoise * options.adaptive->noise + 1e-3 * range;
    a.box = volume.domain;
  }
  return a;
}

std::vector<float> box_limits(const Mesh& mesh, const volume::GridFrame& f,
                              const openvdb::CoordBBox& box, double least) {
  std::vector<float> limit(mesh.positions.size());
  for (std::size_t i = 0; i < limit.size(); ++i) {
    const Vec3f& p = mesh.positions[i];
    const openvdb::Vec3d q = f.to_index(openvdb::Vec3d(p[0], p[1], p[2]));
    double d = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
      d = std::min(d, std::min(q[a] - box.min()[a], box.max()[a] - q[a]) * f.spacing[a]);
    limit[i] = float(std::max(d / kBorderDeviations, least));
  }
  return limit;
}

CutIndex::CutIndex(const Mesh& mesh, const VertexCorners& corners, const volume::GridFrame& frame) {
  if (!frame.clamp) return;  // a sparse grid's data does not stop at a box
  const std::vector<std::uint8_t> open = boundary_vertices(mesh, corners);
  for (std::size_t i = 0; i < open.size(); ++i)
    if (open[i]) points.push_back(mesh.positions[i]);
}

bool CutIndex::near(const Vec3f& p, double radius) const {
  // Brute force over the cut's vertices would be O(n * m); bucket them by cells of `radius`.
  if (points.empty()) return false;
  if (radius != cell) {
    cell = radius;
    buckets.clear();
    for (const Vec3f& q : points) buckets[key(q)].push_back(q);
  }
  const double r2 = radius * radius;
  const auto c = cell_of(p);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = buckets.find(pack(c[0] + dx, c[1] + dy, c[2] + dz));
        if (it == buckets.end()) continue;
        for (const Vec3f& q : it->second) {
          const double x = q[0] - p[0], y = q[1] - p[1], z = q[2] - p[2];
          if (x * x + y * y + z * z <= r2) return true;
        }
      }
  return false;
}

std::array<std::int64_t, 3> CutIndex::cell_of(const Vec3f& p) const {
  return {std::int64_t(std::floor(p[0] / cell)), std::int64_t(std::floor(p[1] / cell)),
          std::int64_t(std::floor(p[2] / cell))};
}

std::uint64_t CutIndex::pack(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto u = [](std::int64_t v) { return std::uint64_t(v + (1 << 20)) & 0x1fffff; };
  return (u(z) << 42) | (u(y) << 21) | u(x);
}

std::uint64_t CutIndex::key(const Vec3f& p) const {
  const auto c = cell_of(p);
  return pack(c[0], c[1], c[2]);
}

namespace {

/// Records whether the scale `sigma` fits vertex i of `mesh`, evaluated as entry j of `e`
/// (volume_estimate.h): eroded, opposed (against `face`, its area-weighted normal); and whether
/// its smoothing reaches the box's cut (flagged Boundary, not a reason for a finer scale).
/// Returns true when it does not fit.
bool record_fit(const VolumeEvaluation& e, std::size_t j, const Mesh& mesh, std::size_t i,
                const Vec3f& face, const VolumeSetup& setup, double sigma, const CutIndex& cut,
                ScaleLadder& ladder) {
  const Vec3f& n = e.field.normals[j];
  ladder.scale[i] = float(sigma);
  // On the voxel staircase (surface) a vertex may lie half a voxel diagonal off the surface.
  const double allowed =
      kMaxShiftScales * sigma + (setup.point == VolumePoint::surface ? 0.87 * setup.voxel : 0.0);
  ladder.eroded[i] = !(std::abs(double(e.raw.shift[j])) <= allowed);
  ladder.opposed[i] = double(n[0]) * face[0] + double(n[1]) * face[1] + double(n[2]) * face[2] < 0;
  ladder.outside[i] = cut.near(mesh.positions[i], kSupportDeviations * sigma);
  return ladder.eroded[i] || ladder.opposed[i];
}

/// Copies entry j of `from` into vertex i of `all`.
void copy_vertex(const VolumeEvaluation& from, std::size_t j, VolumeEvaluation& all,
                 std::size_t i) {
  CurvatureField& f = all.field;
  const CurvatureField& g = from.field;
  f.normals[i] = g.normals[j], f.k1[i] = g.k1[j], f.k2[i] = g.k2[j];
  f.dir1[i] = g.dir1[j], f.dir2[i] = g.dir2[j], f.H[i] = g.H[j], f.K[i] = g.K[j];
  f.dcurv[i] = g.dcurv[j], f.shape_index[i] = g.shape_index[j];
  f.curvedness[i] = g.curvedness[j], f.ao[i] = g.ao[j];
  if (!f.surface_points.empty()) f.surface_points[i] = g.surface_points[j];
  all.raw.gradient_norm[i] = from.raw.gradient_norm[j];
  all.raw.shift[i] = from.raw.shift[j];
}

/// The positions of `mesh`'s vertices `which`, in that order.
Positions positions_of(const Mesh& mesh, const std::vector<std::size_t>& which) {
  Positions p(which.size());
  for (std::size_t j = 0; j < which.size(); ++j) p[j] = mesh.positions[which[j]];
  return p;
}

void add_costs(const VolumeEvaluation& from, VolumeEvaluation& all) {
  all.bricks += from.bricks;
  all.steps.plan += from.steps.plan, all.steps.gather += from.steps.gather;
  all.steps.smooth += from.steps.smooth, all.steps.vertices += from.steps.vertices;
}

}  // namespace

VolumeEvaluation evaluate_with_finer_scales(const Mesh& mesh, const VertexCorners& corners,
                                            VolumeSetup setup, bool finer_scales,
                                            const VolumeEvaluate& evaluate, ScaleLadder& ladder,
                                            const AdaptiveScale* adaptive) {
  const std::size_t nv = mesh.positions.size();
  const std::optional<PilotScales> pilots =
      adaptive && finer_scales ? pilot_scales(*adaptive, setup.sigma) : std::nullopt;
  // The first evaluation: at the asked scale, or at the first pilot.
  const double s1 = pilots ? pilots->p1 : setup.sigma;
  VolumeEvaluation all = evaluate(mesh.positions, pilots ? with_sigma(setup, s1) : setup);
  const std::vector<Vec3f> faces = area_weighted_normals(mesh);
  const CutIndex cut(mesh, corners, setup.frame);
  ladder.scale.assign(nv, 0.0f);
  ladder.eroded.assign(nv, 0), ladder.opposed.assign(nv, 0), ladder.outside.assign(nv, 0);
  ladder.refined = 0;
  // Evaluates the vertices `which` each at its scale `at[i]` (grouped by scale, each group one
  // evaluation), keeps the results in `all`, and returns those the scale does not fit.
  auto evaluate_at = [&](const std::vector<std::size_t>& which, const std::vector<float>& at) {
    std::map<float, std::vector<std::size_t>> groups;
    for (std::size_t i : which) groups[at[i]].push_back(i);
    std::vector<std::size_t> misfits;
    for (const auto& [sigma, members] : groups) {
      const VolumeEvaluation e = evaluate(positions_of(mesh, members), with_sigma(setup, sigma));
      add_costs(e, all);
      for (std::size_t j = 0; j < members.size(); ++j) {
        copy_vertex(e, j, all, members[j]);
        if (record_fit(e, j, mesh, members[j], faces[members[j]], setup, sigma, cut, ladder))
          misfits.push_back(members[j]);
      }
    }
    std::sort(misfits.begin(), misfits.end());
    return misfits;
  };
  std::vector<std::size_t> which;  // the vertices their scale does not fit
  for (std::size_t i = 0; i < nv; ++i)
    if (record_fit(all, i, mesh, i, faces[i], setup, s1, cut, ladder)) which.push_back(i);
  std::vector<float> assigned(nv, float(s1));  // the scale each vertex was first given
  // Surface points (VolumePoint::surface) stay those of s1 where s1 fits: the shrinkage
  // correction that places them is fitted up to sigma kappa = 1/3, while the per-vertex scale goes
  // to kBinaryShapeScale (at 0.5, a binary ball's volume came out 2.6% short).
  std::vector<Vec3f> first_points;
  std::vector<std::uint8_t> fits_first(nv, 1);
  for (std::size_t i : which) fits_first[i] = 0;
  if (pilots) {
    first_points = all.field.surface_points;
    const double s2 = pilots->p2;
    // The second pilot only measures the bias, averaged over regions far wider than the noise's
    // correlation: a sample of the vertices does (pilot_sample), the same whatever their order.
    std::vector<std::size_t> sample;
    for (std::size_t i = 0; i < nv; ++i)
      if (pilot_sample(mesh.positions[i])) sample.push_back(i);
    const VolumeEvaluation e2 = evaluate(positions_of(mesh, sample), with_sigma(setup, s2));
    add_costs(e2, all);
    std::vector<float> H2(nv, std::numeric_limits<float>::quiet_NaN()), g2(nv, 0.0f);
    std::vector<std::int64_t> in_sample(nv, -1);
    for (std::size_t j = 0; j < sample.size(); ++j) {
      H2[sample[j]] = e2.field.H[j], g2[sample[j]] = e2.raw.gradient_norm[j];
      in_sample[sample[j]] = std::int64_t(j);
    }
    ScaleChoiceReport report;
    // The shape's curvature: the first pilot's (on grey levels, at twice the scale the noise asks
    // for, the noise no longer inflates it: the smaller of both pilots' chose the same scales on
    // bench_accuracy's classes).
    std::vector<float> kappa(nv);
    for (std::size_t i = 0; i < nv; ++i)
      kappa[i] = std::max(std::abs(all.field.k1[i]), std::abs(all.field.k2[i]));
    const std::vector<float> limit = adaptive->border_varies
                                         ? box_limits(mesh, setup.frame, adaptive->box, setup.sigma)
                                         : std::vector<float>();
    ScalePilots p{s1,  s2,  &all.field.H, &all.raw.gradient_norm,
                  &H2, &g2, &kappa,       adaptive->border_varies ? &limit : nullptr};
    p.stride = kPilotStride;
    assigned = choose_vertex_scales(
        mesh.positions, adaptive->model, p,
        adaptive->model.staircase ? s1 : std::max(setup.floor, setup.sigma / kUnderPilot),
        adaptive->hi, adaptive->piece, &report);
    ladder.blur = report.blur;
    std::vector<std::size_t> others, next;
    for (std::size_t i = 0; i < nv; ++i) {
      if (assigned[i] == float(s1)) {
        if (ladder.eroded[i] || ladder.opposed[i]) next.push_back(i);
      } else if (assigned[i] == float(s2) && in_sample[i] >= 0) {
        const std::size_t j = std::size_t(in_sample[i]);
        copy_vertex(e2, j, all, i);
        if (record_fit(e2, j, mesh, i, faces[i], setup, s2, cut, ladder)) next.push_back(i);
      } else {
        others.push_back(i);
      }
    }
    const std::vector<std::size_t> more = evaluate_at(others, assigned);
    next.insert(next.end(), more.begin(), more.end());
    std::sort(next.begin(), next.end());
    which.swap(next);
  }
  // Below the floor only the opposed vertices go on, to the reconstruction's own limit: there the
  // field is the samples' B-spline, whose gradient agrees with the marching-cubes surface.
  const double last = std::min(setup.floor, 1.01 * volume::kMinScaleVoxels * setup.voxel);
  // Compared as the floats the ladder keeps, and only ever downwards, so that the loop ends.
  const float floor_f = float(setup.floor), last_f = float(last);
  std::vector<float> at(nv, 0.0f);
  while (finer_scales && !which.empty()) {
    std::vector<std::size_t> go;
    for (std::size_t i : which) {
      const float current = ladder.scale[i];
      if (current <= last_f) continue;
      if (current <= floor_f) {
        if (!ladder.opposed[i]) continue;
        at[i] = last_f;
      } else {
        at[i] = std::max(float(current / kScaleStep), floor_f);
      }
      if (at[i] < current) go.push_back(i);
    }
    which = evaluate_at(go, at);
  }
  if (!first_points.empty())
    for (std::size_t i = 0; i < nv; ++i)
      if (fits_first[i] && ladder.scale[i] >= float(s1))
        all.field.surface_points[i] = first_points[i];
  for (std::size_t i = 0; i < nv; ++i)
    if (ladder.scale[i] < assigned[i]) ++ladder.refined;
  return all;
}

namespace {

/// Vertex i's curvature for the opposite normal: n -> -n, (k1, k2) -> (-k2, -k1) with dir1 and
/// dir2 swapped (so that dir1 x dir2 = n still), dcurv in the swapped, negated frame.
void flip_orientation(std::size_t i, float ao_scale, CurvatureField& f) {
  const Vec3f n = f.normals[i];
  f.normals[i] = Vec3f{-n[0], -n[1], -n[2]};
  const float k1 = -f.k2[i], k2 = -f.k1[i];
  f.k1[i] = k1, f.k2[i] = k2, f.H[i] = -f.H[i];
  std::swap(f.dir1[i], f.dir2[i]);
  const std::array<float, 4> c = f.dcurv[i];
  f.dcurv[i] = {-c[3], -c[2], -c[1], -c[0]};
  f.shape_index[i] = shape_index(k1, k2);
  f.ao[i] = ambient_occlusion(k1, k2, ao_scale);
}

}  // namespace

std::size_t finish_volume_field(const Mesh& mesh, const VertexCorners& corners,
                                const RawVertex& raw, const ScaleLadder& ladder, bool finer_scales,
                                float ao_scale, CurvatureField& field, const SurfacePiece* piece) {
  const std::size_t nv = mesh.positions.size();
  field.area = mixed_vertex_areas(mesh, corners);
  field.boundary = boundary_vertices(mesh, corners);
  for (std::size_t i = 0; i < nv; ++i)
    if (ladder.outside[i]) field.boundary[i] = 1;
  field.unreliable.assign(nv, 0);
  std::vector<float> lengths;  // the vertices' gradients (the whole surface's with a piece)
  lengths.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i)
    if (raw.gradient_norm[i] > 0 && owns_vertex(piece, i)) lengths.push_back(raw.gradient_norm[i]);
  float weak_below = 0;
  if (const std::uint64_t n = total_count(piece, lengths.size()); n > 0)
    weak_below = float(volume::kWeakGradientFraction) *
                 kth_smallest_positive(piece, std::move(lengths), n / 2);
  std::vector<Vec3f> faces;
  std::size_t count = 0;
  for (std::size_t i = 0; i < nv; ++i) {
    // With finer scales an eroded vertex keeps the floor's values, and one still opposed at the
    // reconstruction's limit takes the level set through it oriented as the mesh says.
    const bool weak = !(raw.gradient_norm[i] > weak_below);
    if (!weak && finer_scales && ladder.opposed[i]) {
      flip_orientation(i, ao_scale, field);
      continue;
    }
    const bool bad = weak || (!finer_scales && (ladder.opposed[i] || ladder.eroded[i]));
    if (!bad) continue;
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
    if (!field.surface_points.empty()) field.surface_points[i] = mesh.positions[i];
  }
  if (finer_scales) field.extra.push_back({"Scale", ladder.scale});
  return count;
}

}  // namespace detail

}  // namespace isocurv::curvature
