#include "volume/prefilter.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/floor_div8.h"

namespace isocurv::volume {
namespace {

openvdb::Coord first_voxel(const openvdb::Coord& b) { return {b[0] * 8, b[1] * 8, b[2] * 8}; }

// The sampled Gaussian of deviation s, truncated at kPrefilterRadius deviations (at least one tap
// each side), normalised to sum 1.
PrefilterTaps sampled_gaussian(double s) {
  PrefilterTaps t;
  t.radius = std::min(kPrefilterMaxRadius, std::max(1, int(std::ceil(kPrefilterRadius * s))));
  t.w.assign(2 * t.radius + 1, 0.0);
  double sum = 0;
  for (int k = -t.radius; k <= t.radius; ++k)
    sum += t.w[k + t.radius] = std::exp(-k * k / (2 * s * s));
  for (double& w : t.w) w /= sum;
  return t;
}

double discrete_variance(const PrefilterTaps& t) {
  double v = 0;
  for (int k = -t.radius; k <= t.radius; ++k) v += double(k) * k * t.w[k + t.radius];
  return v;
}

// Brick coordinates of the bricks a pass along `axis` reads for the output bricks `out`: each
// output voxel v reads v + k for |k| <= radius, clamped to the domain along that axis when the
// frame clamps. Sorted in table order (z, then y, then x), no duplicates.
std::vector<openvdb::Coord> pass_inputs(const std::vector<openvdb::Coord>& out, int axis,
                                        int radius, const GridFrame& frame) {
  std::vector<openvdb::Coord> in;
  for (const openvdb::Coord& b : out) {
    long lo = 8L * b[axis] - radius, hi = 8L * b[axis] + 7 + radius;
    if (frame.clamp) {
      lo = std::clamp<long>(lo, frame.lo[axis], frame.hi[axis]);
      hi = std::clamp<long>(hi, frame.lo[axis], frame.hi[axis]);
    }
    for (int c = floor_div8(int(lo)); c <= floor_div8(int(hi)); ++c) {
      openvdb::Coord r = b;
      r[axis] = c;
      in.push_back(r);
    }
  }
  auto order = [](const openvdb::Coord& a, const openvdb::Coord& b) {
    if (a[2] != b[2]) return a[2] < b[2];
    return a[1] != b[1] ? a[1] < b[1] : a[0] < b[0];
  };
  std::sort(in.begin(), in.end(), order);
  in.erase(std::unique(in.begin(), in.end()), in.end());
  return in;
}

// The bricks holding every voxel within `reach` of each point's index position, in table order.
std::vector<openvdb::Coord> point_bricks(const GridFrame& frame, const Positions& points,
                                         const openvdb::Vec3d& reach) {
  const std::size_t n = points.size();
  std::vector<openvdb::CoordBBox> boxes(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f& p = points[i];
      const openvdb::Vec3d q = frame.to_index(openvdb::Vec3d(p[0], p[1], p[2]));
      openvdb::Coord lo, hi;
      for (int a = 0; a < 3; ++a) {
        const double l = std::clamp(std::floor(q[a] - reach[a]), -1e9, 1e9);
        const double h = std::clamp(std::ceil(q[a] + reach[a]), -1e9, 1e9);
        lo[a] = floor_div8(int(l)), hi[a] = floor_div8(int(h));
      }
      boxes[i] = openvdb::CoordBBox(lo, hi);
    }
  });
  openvdb::CoordBBox all = boxes[0];
  for (const openvdb::CoordBBox& b : boxes) all.expand(b);
  const openvdb::Coord dims = all.dim();
  if (double(dims[0]) * dims[1] * dims[2] > double(std::numeric_limits<std::int32_t>::max()))
    throw Error("volume: the surface's filter windows span too large a region");
  std::vector<std::uint8_t> mark(std::size_t(dims[0]) * dims[1] * dims[2], 0);
  for (const openvdb::CoordBBox& b : boxes)
    for (int z = b.min()[2]; z <= b.max()[2]; ++z)
      for (int y = b.min()[1]; y <= b.max()[1]; ++y) {
        const std::size_t row =
            (std::size_t(z - all.min()[2]) * dims[1] + (y - all.min()[1])) * dims[0];
        for (int x = b.min()[0]; x <= b.max()[0]; ++x) mark[row + (x - all.min()[0])] = 1;
      }
  std::vector<openvdb::Coord> bricks;
  for (std::size_t c = 0; c < mark.size(); ++c)
    if (mark[c]) {
      const int x = int(c % dims[0]), y = int((c / dims[0]) % dims[1]),
                z = int(c / (std::size_t(dims[0]) * dims[1]));
      bricks.push_back(all.min() + openvdb::Coord(x, y, z));
    }
  return bricks;
}

}  // namespace

std::ptrdiff_t SmoothingPlan::sample_index(const BrickSet& set, const openvdb::Coord& voxel) const {
  const openvdb::Coord b(floor_div8(voxel[0]), floor_div8(voxel[1]), floor_div8(voxel[2]));
  if (!in_region(b)) return -1;
  const std::int32_t n = set.table[cell(b)];
  if (n < 0) return -1;
  const openvdb::Coord l = voxel - first_voxel(b);
  return std::ptrdiff_t(n) * 512 + (l[2] * 8 + l[1]) * 8 + l[0];
}

PrefilterTaps prefilter_taps(double variance) {
  if (!(variance >= 0) || !std::isfinite(variance))
    throw Error("volume: a prefilter variance must be finite and not negative, not " +
                std::to_string(variance));
  if (variance == 0) return {};
  // The discrete variance grows with the deviation: bisect for the one that gives `variance`.
  double lo = 1e-3, hi = std::sqrt(variance) + 1;
  for (int it = 0; it < 80; ++it) {
    const double mid = (lo + hi) / 2;
    (discrete_variance(sampled_gaussian(mid)) < variance ? lo : hi) = mid;
  }
  return sampled_gaussian((lo + hi) / 2);
}

SmoothingPlan plan_smoothing(const GridFrame& frame, const Positions& world_points,
                             const openvdb::Vec3d& reach, double sigma,
                             const openvdb::Vec3d& own_variance) {
  SmoothingPlan plan;
  plan.frame = frame;
  for (int a = 0; a < 3; ++a) {
    const double deviation = sigma / frame.spacing[a];
    const double variance = deviation * deviation - kSplineVariance - own_variance[a];
    if (!(deviation >= kMinScaleVoxels) || !(variance >= 0))
      throw Error(
          "volume: scale " + std::to_string(sigma) + " is " + std::to_string(deviation) +
          " voxels along index axis " + std::to_string(a) + "; at least " +
          std::to_string(std::max(kMinScaleVoxels, std::sqrt(kSplineVariance + own_variance[a]))) +
          " are supported");
    if (deviation > kMaxPrefilterDeviation)
      throw Error("volume: scale " + std::to_string(sigma) + " is " + std::to_string(deviation) +
                  " voxels along index axis " + std::to_string(a) + "; at most " +
                  std::to_string(int(kMaxPrefilterDeviation)) + " are supported");
    plan.taps[a] = prefilter_taps(variance);
  }
  if (world_points.empty()) return plan;
  openvdb::Vec3d window;
  for (int a = 0; a < 3; ++a) window[a] = reach[a] + kSplineReach;
  plan.stages[3].bricks = point_bricks(frame, world_points, window);
  for (int a = 2; a >= 0; --a)
    plan.stages[a].bricks = pass_inputs(plan.stages[a + 1].bricks, a, plan.taps[a].radius, frame);

  openvdb::CoordBBox all(plan.stages[3].bricks.front(), plan.stages[3].bricks.front());
  for (const BrickSet& s : plan.stages)
    for (const openvdb::Coord& b : s.bricks) all.expand(b);
  plan.origin = all.min();
  plan.dims = all.dim();
  const double cells = double(plan.dims[0]) * plan.dims[1] * plan.dims[2];
  if (cells > double(std::numeric_limits<std::int32_t>::max()))
    throw Error("volume: the surface's filter windows span too large a region");
  for (BrickSet& s : plan.stages) {
    s.table.assign(std::size_t(cells), -1);
    for (std::size_t i = 0; i < s.bricks.size(); ++i)
      s.table[plan.cell(s.bricks[i])] = std::int32_t(i);
  }
  return plan;
}

std::vector<float> gather_stage_samples(const openvdb::FloatGrid& grid, const SmoothingPlan& plan) {
  std::vector<float> out;
  gather_bricks(grid, plan.frame, plan.stages[0].bricks, out);
  return out;
}

void gather_bricks(const openvdb::FloatGrid& grid, const GridFrame& f,
                   const std::vector<openvdb::Coord>& bricks, std::vector<float>& all) {
  const std::size_t start = all.size();
  all.resize(start + bricks.size() * 512);
  float* const out = all.data() + start;
  auto inside = [&](const openvdb::Coord& c) {
    for (int a = 0; a < 3; ++a)
      if (c[a] < f.lo[a] || c[a] + 7 > f.hi[a]) return false;
    return true;
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bricks.size(), 16), [&](const auto& r) {
    openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      float* dst = out + b * 512;
      const openvdb::Coord origin = first_voxel(bricks[b]);
      if (!f.clamp || inside(origin)) {
        // A brick is exactly one of OpenVDB's 8^3 leaves (or lies in one tile): copy the leaf,
        // whose voxel (x, y, z) is at (x * 8 + y) * 8 + z, into x-fastest order.
        if (const openvdb::FloatTree::LeafNodeType* leaf = acc.probeConstLeaf(origin)) {
          const float* v = leaf->buffer().data();
          for (int x = 0; x < 8; ++x)
            for (int y = 0; y < 8; ++y)
              for (int z = 0; z < 8; ++z) dst[(z * 8 + y) * 8 + x] = v[(x * 8 + y) * 8 + z];
        } else {
          std::fill(dst, dst + 512, acc.getValue(origin));
        }
        continue;
      }
      for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
          for (int x = 0; x < 8; ++x) {
            openvdb::Coord c = origin + openvdb::Coord(x, y, z);
            for (int a = 0; a < 3; ++a) c[a] = std::clamp(c[a], f.lo[a], f.hi[a]);
            dst[(z * 8 + y) * 8 + x] = acc.getValue(c);
          }
    }
  });
}

SmoothedSamples smooth_reference(const openvdb::FloatGrid& grid, const SmoothingPlan& plan) {
  SmoothedSamples s;
  s.plan = &plan;
  s.background = grid.background();
  const std::vector<float> raw = gather_stage_samples(grid, plan);
  std::vector<double> in(raw.begin(), raw.end());
  const GridFrame& f = plan.frame;
  for (int a = 0; a < 3; ++a) {
    const BrickSet& from = plan.stages[a];
    const BrickSet& to = plan.stages[a + 1];
    const PrefilterTaps& taps = plan.taps[a];
    std::vector<double> out(to.bricks.size() * 512);
    auto read = [&](openvdb::Coord c) {
      if (f.clamp) c[a] = std::clamp(c[a], f.lo[a], f.hi[a]);
      const std::ptrdiff_t i = plan.sample_index(from, c);
      return i < 0 ? s.background : in[std::size_t(i)];
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, to.bricks.size(), 16), [&](const auto& r) {
      for (std::size_t b = r.begin(); b != r.end(); ++b)
        for (int v = 0; v < 512; ++v) {
          const openvdb::Coord c =
              first_voxel(to.bricks[b]) + openvdb::Coord(v & 7, (v >> 3) & 7, v >> 6);
          double sum = 0;
          for (int k = -taps.radius; k <= taps.radius; ++k) {
            openvdb::Coord t = c;
            t[a] += k;
            sum += taps.w[k + taps.radius] * read(t);
          }
          out[b * 512 + v] = sum;
        }
    });
    in = std::move(out);
  }
  s.samples = std::move(in);
  return s;
}

}  // namespace isocurv::volume
