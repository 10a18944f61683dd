// features::compute: the driver. Per radius, per vertex: the ball's surface
// samples (LBE, NSV, the mesh form of H_ii), the volume quadrature (Vr, H_ii),
// the geodesic disc (K_ii), then SI_ii.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/error.h"
#include "core/mesh_measures.h"
#include "core/progress.h"
#include "features/detail/ball_samples.h"
#include "features/detail/geodesic_disc.h"
#include "features/detail/geodesic_web.h"
#include "features/detail/mesh_graph.h"
#include "features/detail/sampled_device.h"
#include "features/detail/volume_ball.h"
#include "features/features.h"

namespace isocurv::features {
namespace {

constexpr double kPi = 3.14159265358979323846;
/// Vertices per parallel pass between progress updates (the bar is advanced on
/// this thread).
constexpr std::size_t kProgressBlock = 8192;

bool wants(const Options &o, Feature f) {
  return std::find(o.features.begin(), o.features.end(), f) != o.features.end();
}

double max_edge_length(const Mesh &mesh) {
  double m = 0;
  for (const Tri &t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const Vec3f &a = mesh.positions[t[c]],
                  &b = mesh.positions[t[(c + 1) % 3]];
      const double d0 = double(a[0]) - b[0], d1 = double(a[1]) - b[1],
                   d2 = double(a[2]) - b[2];
      m = std::max(m, d0 * d0 + d1 * d1 + d2 * d2);
    }
  return std::sqrt(m);
}

std::string radius_label(const Options &o, std::size_t i) {
  if (i < o.radius_names.size() && !o.radius_names[i].empty())
    return o.radius_names[i];
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", o.radii[i]);
  return buf;
}

/// Shape index from a mean and a Gaussian curvature (eq. 8-9, minus signs
/// restored).
float shape_index(double H, double K) {
  const double root = std::sqrt(std::max(0.0, H * H - K));
  const double k1 = H + root, k2 = H - root;
  if (k1 == k2 && k1 == 0)
    return 0;
  return static_cast<float>(2 / kPi * std::atan2(k1 + k2, k1 - k2));
}

/// Area of a geodesic disc of radius r on a surface of constant Gaussian
/// curvature K: 2 pi (1 - cos(r sqrt K)) / K, pi r^2 at K = 0, 2 pi (cosh(r
/// sqrt -K) - 1) / -K below.
double disc_area(double K, double r) {
  const double x = K * r * r;
  if (std::abs(x) < 1e-4)
    return kPi * r * r * (1 - x / 12 + x * x / 360);
  return K > 0 ? 2 * kPi * (1 - std::cos(r * std::sqrt(K))) / K
               : 2 * kPi * (std::cosh(r * std::sqrt(-K)) - 1) / -K;
}

/// The Gaussian curvature whose constant-curvature disc of radius r has area
/// `area`. Its first term is Bertrand-Diquet-Puiseux, 12 (pi r^2 - area) / (pi
/// r^4) (eq. 10); solving the disc formula instead removes that series' -K^2
/// r^2 / 30 bias, so a sphere gives exactly 1/R^2 (and a sphere's shape index
/// exactly 1 with an exact H). Newton from the series value, K kept below (pi /
/// r)^2 where the disc would cover the whole sphere.
double gaussian_from_disc_area(double area, double r) {
  const double k_max = 0.999 * (kPi / r) * (kPi / r);
  double K = std::min(12 * (kPi * r * r - area) / (kPi * r * r * r * r), k_max);
  for (int it = 0; it < 30; ++it) {
    const double h = 1e-6 / (r * r);
    const double f = disc_area(K, r) - area;
    const double df = (disc_area(K + h, r) - disc_area(K - h, r)) / (2 * h);
    if (!(df < 0))
      break;
    const double step = f / df;
    K = std::min(K - step, k_max);
    if (std::abs(step) < 1e-12 / (r * r))
      break;
  }
  return K;
}

/// Per-thread scratch.
struct Scratch {
  std::vector<std::uint32_t> stamp, queue;
  std::uint32_t mark = 0;
  detail::GeodesicScratch geodesic;
  std::optional<detail::VolumeBall> ball;
};

/// Everything one vertex's features need at one radius.
struct VertexResult {
  float lbe = 0, nsv = 0.5f, vr = 0, h = 0, k = 0;
  bool boundary = false;
};

/// The sampled path's curves per vertex: samples / kWebSteps, even, at least 2.
int web_azimuths(int samples) { return std::max(2, (samples / detail::kWebSteps) & ~1); }

/// compute() on the host (device == nullptr) or with its kernels on `device`.
FeatureField compute_on(const Mesh& mesh, const curvature::CurvatureField& field,
                        const volume::Volume* volume, const Options& options, Device* device) {
  const std::size_t n = mesh.vertex_count();
  if (field.normals.size() != n || field.area.size() != n)
    throw Error("features need the curvature field's Normals and Area for "
                "every vertex");
  if (options.radii.empty())
    throw Error("features need at least one radius");
  Options o = options;
  if (o.features.empty()) {
    for (Feature f : {Feature::LBE, Feature::NSV, Feature::Vr, Feature::H_ii,
                      Feature::K_ii, Feature::SI_ii})
      if (f != Feature::Vr || volume)
        o.features.push_back(f);
  }
  if (wants(o, Feature::Vr) && !volume)
    throw Error("Vr (the volume integral invariant) needs a volume; mesh input "
                "gives LBE, NSV, "
                "H_ii (surface form), K_ii and SI_ii");
  const bool sampled = o.samples != 0;
  if (sampled && !volume)
    throw Error(
        "sampled neighbourhoods (--samples) need a volume; for a mesh "
        "file use --samples 0 (the exact neighbourhoods)");
  if (sampled && o.samples < 2 * detail::kWebSteps)
    throw Error("--samples must be 0 (exact) or at least " + std::to_string(2 * detail::kWebSteps) +
                ", got " + std::to_string(o.samples));
  if (!(o.adaptive_threshold >= 0) || !std::isfinite(o.adaptive_threshold))
    throw Error("the adaptive sampling threshold must be >= 0");
  const double diagonal = bounding_box_diagonal(mesh);
  for (std::size_t i = 0; i < o.radii.size(); ++i) {
    const double r = o.radii[i];
    if (!(r > 0) || !std::isfinite(r))
      throw Error("radius " + radius_label(o, i) + " is not positive");
    if (n > 0 && r > diagonal)
      throw Error("radius " + radius_label(o, i) +
                  " is larger than the surface (bounding-box diagonal " +
                  std::to_string(diagonal) + ")");
  }

  const bool need_ball =
      wants(o, Feature::LBE) || wants(o, Feature::NSV) ||
      (!volume && (wants(o, Feature::H_ii) || wants(o, Feature::SI_ii)));
  const bool need_volume =
      volume && (wants(o, Feature::Vr) || wants(o, Feature::H_ii) ||
                 wants(o, Feature::SI_ii));
  const bool need_disc = wants(o, Feature::K_ii) || wants(o, Feature::SI_ii);
  const bool need_web = sampled && (need_ball || need_disc);
  // The volume's dense samples, for the web and the device's quadrature.
  std::optional<volume::DenseField> dense;
  if (n > 0 && (need_web || (device && need_volume))) dense.emplace(*volume);
  const int azimuths = web_azimuths(o.samples);
  const float iso = static_cast<float>(o.isovalue);
  std::uint64_t curves = 0, curves_full = 0;

  const detail::MeshGraph graph = detail::build_mesh_graph(mesh);
  const double max_edge = max_edge_length(mesh);
  FeatureField out;
  out.boundary.assign(n, 0);
  tbb::enumerable_thread_specific<Scratch> scratch;
  std::vector<VertexResult> results(n);

  for (std::uint32_t v : o.vertices)
    if (v >= n) throw Error("features: vertex " + std::to_string(v) + " is not in the mesh");
  const std::size_t todo = o.vertices.empty() ? n : o.vertices.size();
  // Progress in vertex passes: the host loop, plus the web and the device's quadrature.
  const std::size_t passes = 1 + (need_web ? 1 : 0) + (device && need_volume ? 1 : 0);
  Progress progress("features", todo * o.radii.size() * passes);
  const detail::ProgressFn advance = [&](std::size_t done) { progress.advance(done); };
  for (std::size_t ri = 0; ri < o.radii.size(); ++ri) {
    const double r = o.radii[ri];
    // The batched parts: the web (device or reference) and the device's
    // quadrature.
    std::vector<detail::WebSums> web;
    if (need_web && n > 0) {
      if (device) {
        web = detail::web_on_device(*device, *dense, iso, mesh, field.normals, r, azimuths,
                                    o.adaptive, o.adaptive_threshold, o.seed, 64, advance);
      } else {
        web.resize(n);
        for (std::size_t block = 0; block < todo; block += kProgressBlock) {
          const std::size_t block_end = std::min(todo, block + kProgressBlock);
          tbb::parallel_for(
              tbb::blocked_range<std::size_t>(block, block_end, 64), [&](const auto& range) {
                for (std::size_t i = range.begin(); i != range.end(); ++i) {
                  const std::size_t v = o.vertices.empty() ? i : o.vertices[i];
                  const Vec3f &p = mesh.positions[v], &nv = field.normals[v];
                  web[v] = detail::trace_web(*dense, iso, {p[0], p[1], p[2]}, {nv[0], nv[1], nv[2]},
                                             r, azimuths, o.adaptive, o.adaptive_threshold,
                                             static_cast<std::uint32_t>(v), o.seed);
                }
              });
          progress.advance(block_end - block);
        }
      }
      for (std::size_t i = 0; i < todo; ++i)
        curves += std::uint64_t(web[o.vertices.empty() ? i : o.vertices[i]].azimuths);
      curves_full += std::uint64_t(todo) * azimuths;
    }
    detail::BallOnDevice device_ball;
    if (device && need_volume && n > 0) {
      const detail::VolumeBall quadrature(*volume, o.isovalue, o.azimuths, o.radial);
      device_ball = detail::ball_on_device(*device, *dense, iso, mesh, field.normals, r, o.azimuths,
                                           quadrature.nodes(), quadrature.weights(), 64, advance);
    }
    for (std::size_t block = 0; block < todo; block += kProgressBlock) {
      const std::size_t block_end = std::min(todo, block + kProgressBlock);
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(block, block_end, 64),
          [&](const auto &range) {
            Scratch &s = scratch.local();
            if (s.stamp.size() != n)
              s.stamp.assign(n, 0), s.mark = 0;
            if (need_volume && !device && !s.ball)
              s.ball.emplace(*volume, o.isovalue, o.azimuths, o.radial);
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
              const std::size_t v = o.vertices.empty() ? i : o.vertices[i];
              VertexResult &res = results[v];
              res = VertexResult{};
              const Vec3f &nv = field.normals[v];
              if (nv[0] == 0 && nv[1] == 0 &&
                  nv[2] == 0) { // isolated: nothing to measure
                res.boundary = true;
                continue;
              }
              if (!web.empty()) {
                const detail::WebSums& w = web[v];
                res.boundary = res.boundary || w.boundary;
                res.lbe = static_cast<float>(w.lbe);
                res.nsv = static_cast<float>(w.nsv);
                if (need_disc) res.k = static_cast<float>(gaussian_from_disc_area(w.disc_area, r));
              } else if (need_ball) {
                if (++s.mark == 0)
                  std::fill(s.stamp.begin(), s.stamp.end(), 0), s.mark = 1;
                const detail::BallSums b = detail::ball_sums(
                    mesh, graph, field.normals, field.area,
                    static_cast<std::uint32_t>(v), r, s.stamp, s.mark, s.queue);
                res.boundary = res.boundary || b.touches_boundary;
                if (b.horizon_area > 0) {
                  res.lbe = static_cast<float>(b.bending / b.horizon_area);
                  res.nsv = static_cast<float>(b.horizon / b.horizon_area);
                }
                if (!volume && b.area > 0)
                  res.h = static_cast<float>(-4 / (r * r) * b.height / b.area);
              }
              if (need_volume && device) {
                res.boundary = res.boundary || device_ball.leaves[v];
                res.vr = device_ball.vr[v];
                res.h = device_ball.h[v];
              } else if (need_volume) {
                const Vec3f &p = mesh.positions[v];
                const detail::VolumeBall::Result b = s.ball->inside_volume(
                    openvdb::Vec3d(p[0], p[1], p[2]),
                    openvdb::Vec3d(nv[0], nv[1], nv[2]), r);
                res.boundary = res.boundary || b.leaves;
                res.vr = static_cast<float>(b.vr);
                res.h = static_cast<float>(b.h_fit);
              }
              if (need_disc && web.empty()) {
                const detail::GeodesicDisc d = detail::geodesic_disc(
                    mesh, graph, static_cast<std::uint32_t>(v), r, max_edge,
                    s.geodesic);
                res.boundary = res.boundary || d.touches_boundary;
                res.k = static_cast<float>(gaussian_from_disc_area(d.area, r));
              }
            }
          });
      progress.advance(block_end - block);
    }

    const std::string suffix =
        o.radii.size() > 1 ? "_r" + radius_label(o, ri) : "";
    for (Feature f : o.features) {
      if (f == Feature::Vr && !volume)
        continue;
      Array a{feature_name(f) + suffix, std::vector<float>(n)};
      for (std::size_t v = 0; v < n; ++v) {
        const VertexResult &res = results[v];
        switch (f) {
        case Feature::LBE:
          a.values[v] = res.lbe;
          break;
        case Feature::NSV:
          a.values[v] = res.nsv;
          break;
        case Feature::Vr:
          a.values[v] = res.vr;
          break;
        case Feature::H_ii:
          a.values[v] = res.h;
          break;
        case Feature::K_ii:
          a.values[v] = res.k;
          break;
        case Feature::SI_ii:
          a.values[v] = shape_index(res.h, res.k);
          break;
        }
        if (!std::isfinite(a.values[v]))
          a.values[v] = 0, out.boundary[v] = 1;
      }
      out.arrays.push_back(std::move(a));
    }
    for (std::size_t v = 0; v < n; ++v)
      if (results[v].boundary)
        out.boundary[v] = 1;
  }
  out.samples_taken = curves * detail::kWebSteps;
  out.traced_fraction = curves_full > 0 ? double(curves) / curves_full : 1;
  return out;
}

}  // namespace

FeatureField compute(const Mesh& mesh, const curvature::CurvatureField& field,
                     const volume::Volume* volume, const Options& options) {
  return compute_on(mesh, field, volume, options, nullptr);
}

FeatureField compute(const Mesh& mesh, const curvature::CurvatureField& field,
                     const volume::Volume* volume, const Options& options, Device& device) {
  return compute_on(mesh, field, volume, options, &device);
}

} // namespace isocurv::features
