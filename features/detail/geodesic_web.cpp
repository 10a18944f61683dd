#include "features/detail/geodesic_web.h"

#include <algorithm>
#include <cmath>

#include "core/vec3.h"
#include "curvature/detail/local_geometry.h"

namespace isocurv::features::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
using V = std::array<double, 3>;

V add(const V& a, const V& b, double s = 1) {
  return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}
using vec3::dot;
using vec3::cross;
using vec3::norm;

/// The volume read in world space: the signed field and its world gradient at a world point.
struct WorldField {
  const volume::DenseField& f;
  float iso;
  double voxel;  ///< the shortest voxel edge, world units

  double operator()(const V& w, V& grad) const {
    V gi;
    const double v = f.field(f.index(w), iso, &gi);
    const auto& m = f.normal_matrix;
    for (int r = 0; r < 3; ++r)
      grad[r] = m[3 * r] * gi[0] + m[3 * r + 1] * gi[1] + m[3 * r + 2] * gi[2];
    return v;
  }
  bool inside_domain(const V& w) const {
    const V q = f.index(w);
    return q[0] >= 0 && q[1] >= 0 && q[2] >= 0 && q[0] <= f.nx - 1 && q[1] <= f.ny - 1 &&
           q[2] <= f.nz - 1;
  }
};

/// Running trapezoid sums along one curve: weight w = rho / |e . n_c| times each integrand.
struct CurveSums {
  double w = 0, lbe = 0, nsv = 0, height = 0;  ///< over the Euclidean ball
  double disc = 0;                             ///< w over the geodesic disc s <= r
};
/// Per node: the weighted integrands (w, w lbe, w nsv, w height).
using Node = std::array<double, 4>;

/// Traces the curve at azimuth direction u (unit, tangent at p0) and sums it.
CurveSums trace_curve(const WorldField& field, const V& p0, const V& n0, const V& u, double r,
                      bool& boundary) {
  CurveSums out;
  const V m = cross(n0, u);  // the cutting plane's normal
  const double h_max = r / kWebSteps, h_min = h_max / kWebStepDivisions;
  double h = h_max;
  V c = p0, dir = u, grad;
  Node prev = {0, 0, 0, 0};
  double s = 0, dist_prev = 0;
  bool ball_done = false, disc_done = false;
  for (int attempt = 0;
       attempt < kWebMaxAttempts && s < kWebMaxLength * r && !(ball_done && disc_done); ++attempt) {
    // Predict along the curve's direction, correct onto the surface within the plane.
    V c1 = add(c, dir, h);
    bool lost = false;
    for (int it = 0; it < kCorrectorSteps && !lost; ++it) {
      const double f = field(c1, grad);
      const V gp = add(grad, m, -dot(grad, m));
      const double gg = dot(gp, gp);
      // The last step starts within kOffSurface of the surface, or the curve is lost.
      lost = !(gg > 0) ||
             (it == kCorrectorSteps - 1 && std::abs(f) > kOffSurface * field.voxel * norm(grad));
      if (lost) break;
      c1 = add(c1, gp, -f / gg);
      c1 = add(c1, m, -dot(add(c1, p0, -1), m));
    }
    if (lost && h > h_min) {  // the cut turns within the step: try a shorter one
      h *= 0.5;
      continue;
    }
    lost = lost || !field.inside_domain(c1);
    const V step_vec = add(c1, c, -1);
    const double ds = norm(step_vec);
    const V nc = lost ? V{0, 0, 0} : field.f.normal(field.f.index(c1));
    if (lost || !(ds > 0) || (nc[0] == 0 && nc[1] == 0 && nc[2] == 0)) {
      boundary = true;  // the curve stops: its sums so far stand, the vertex is flagged
      break;
    }
    const V d1 = {step_vec[0] / ds, step_vec[1] / ds, step_vec[2] / ds};
    const V q = add(c1, p0, -1);
    const double dist = norm(q), along = dot(q, n0);
    const double rho = std::sqrt(std::max(0.0, dist * dist - along * along));
    const double cosv = std::max(std::abs(dot(cross(m, d1), nc)), kMinCos);
    const double w = rho / cosv;
    const V dn = add(n0, nc, -1);
    const Node node = {w, w * dot(dn, dn) / (dist * dist), w * 0.5 * (1 - along / dist), w * along};
    if (!ball_done) {
      // The part of this step inside the ball |x - p0| <= r (distance taken as linear in it).
      double t = 1;
      if (dist > r) t = (r - dist_prev) / (dist - dist_prev), ball_done = true;
      t = std::clamp(t, 0.0, 1.0);
      double* sums[4] = {&out.w, &out.lbe, &out.nsv, &out.height};
      for (int a = 0; a < 4; ++a)
        *sums[a] += 0.5 * t * ds * (2 * prev[a] + t * (node[a] - prev[a]));
    }
    if (!disc_done) {
      double t = 1;
      if (s + ds >= r) t = (r - s) / ds, disc_done = true;
      out.disc += 0.5 * t * ds * (2 * prev[0] + t * (node[0] - prev[0]));
    }
    s += ds, dist_prev = dist, prev = node, c = c1, dir = d1;
    h = std::min(h_max, 2 * h);
  }
  return out;
}

}  // namespace

bool adaptive_needs_more(double sum, double sum_sq, double sum_cos2, double sum_sin2, int count,
                         double threshold) {
  const double mean = sum / count, mean_sq = sum_sq / count;
  double residual = mean_sq - mean * mean;
  if (count >= 5) {  // evenly spaced azimuths: cos 2 phi and sin 2 phi are orthogonal there
    const double a = 2 * sum_cos2 / count, b = 2 * sum_sin2 / count;
    residual -= 0.5 * (a * a + b * b);
  }
  return residual > threshold * mean_sq;
}

double web_rotation(std::uint32_t vertex, std::uint32_t seed) {
  // lowbias32 (Chris Wellons) of the vertex mixed with the seed; 24 bits of angle.
  std::uint32_t x = vertex ^ (seed * 0x9E3779B9u);
  x ^= x >> 16, x *= 0x7feb352du, x ^= x >> 15, x *= 0x846ca68bu, x ^= x >> 16;
  return 2 * kPi * double(x >> 8) * (1.0 / 16777216.0);
}

WebSums trace_web(const volume::DenseField& vol, float iso, const std::array<double, 3>& p,
                  const std::array<double, 3>& n, double r, int azimuths, bool adaptive,
                  double threshold, std::uint32_t vertex, std::uint32_t seed) {
  WebSums out;
  const WorldField field{vol, iso, vol.shortest_voxel_edge()};
  // The vertex onto the trilinear surface along its normal.
  V p0 = p, grad;
  for (int it = 0; it < kProjectSteps; ++it) {
    const double f = field(p0, grad), gn = dot(grad, n);
    if (!(std::abs(gn) > 0)) break;
    p0 = add(p0, n, std::clamp(-f / gn, -0.5 * field.voxel, 0.5 * field.voxel));
  }
  if (norm(add(p0, p, -1)) > field.voxel) p0 = p;
  V n0 = vol.normal(vol.index(p0));
  if (n0[0] == 0 && n0[1] == 0 && n0[2] == 0) n0 = n;
  Eigen::Vector3d u, v;
  curvature::detail::tangent_basis(Eigen::Vector3d(n0[0], n0[1], n0[2]), u, v);
  const V e1 = {u.x(), u.y(), u.z()}, e2 = {v.x(), v.y(), v.z()};
  const double rotation = web_rotation(vertex, seed);

  CurveSums total;
  double g_sum = 0, g_sq = 0, g_cos = 0, g_sin = 0;
  int g_count = 0;
  auto trace = [&](int k) {
    const double phi = rotation + 2 * kPi * k / azimuths;
    const V u = add(V{std::cos(phi) * e1[0], std::cos(phi) * e1[1], std::cos(phi) * e1[2]}, e2,
                    std::sin(phi));
    const CurveSums c = trace_curve(field, p0, n0, u, r, out.boundary);
    total.w += c.w, total.lbe += c.lbe, total.nsv += c.nsv, total.height += c.height;
    total.disc += c.disc;
    if (c.w > 0) {
      const double g = -4 / (r * r) * c.height / c.w;  // this azimuth's mean curvature
      g_sum += g, g_sq += g * g, ++g_count;
      g_cos += g * std::cos(2 * phi), g_sin += g * std::sin(2 * phi);
    }
    ++out.azimuths;
  };
  for (int k = 0; k < azimuths; k += 2) trace(k);
  bool second = !adaptive;
  if (adaptive && g_count > 0) {
    second = adaptive_needs_more(g_sum, g_sq, g_cos, g_sin, g_count, threshold);
  }
  if (second)
    for (int k = 1; k < azimuths; k += 2) trace(k);
  if (total.w > 0) {
    out.lbe = total.lbe / total.w;
    out.nsv = total.nsv / total.w;
  } else {
    out.boundary = true;
  }
  out.disc_area = 2 * kPi / out.azimuths * total.disc;
  return out;
}

}  // namespace isocurv::features::detail
