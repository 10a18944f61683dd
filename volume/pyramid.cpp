// The scale-space pyramid (pyramid.h).
#include "volume/pyramid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/floor_div8.h"
#include "volume/prefilter.h"

namespace isocurv::volume {
namespace {

int ceil_div2(int v) { return v >= 0 ? (v + 1) / 2 : -((-v) / 2); }
int floor_div2(int v) { return v >= 0 ? v / 2 : -((-v + 1) / 2); }

/// The range of level k - 1 coordinates that level k's brick coordinate `b` reads along an axis.
struct Span {
  int lo = 0, hi = 0;
};
Span parent_span(int b, bool decimated, int radius) {
  if (!decimated) return {8 * b, 8 * b + 7};
  return {16 * b - radius, 16 * b + 14 + radius};
}

}  // namespace

std::size_t Pyramid::CoordHash::operator()(const openvdb::Coord& c) const {
  std::uint64_t h = std::uint64_t(std::uint32_t(c[0]));
  h = h * 0x9e3779b97f4a7c15ull ^ std::uint32_t(c[1]);
  h = h * 0x9e3779b97f4a7c15ull ^ std::uint32_t(c[2]);
  return std::size_t(h ^ (h >> 29));
}

Pyramid::Pyramid(const Volume& volume) {
  PyramidLevel base;
  base.grid = volume.grid;
  base.frame = grid_frame(volume);
  levels_.push_back(base);
  const double finest =
      std::min({base.frame.spacing[0], base.frame.spacing[1], base.frame.spacing[2]});
  const PrefilterTaps taps = prefilter_taps(kPyramidVariance);
  decimation_.assign(taps.w.begin(), taps.w.end());
  decimation_radius_ = taps.radius;
  const int radius = taps.radius;
  // The samples 2 j inside the finer level's own (not extended) box, per axis: what decides
  // whether an axis still has room to halve.
  openvdb::Coord inner_lo = base.frame.lo, inner_hi = base.frame.hi;
  const bool boxed = !volume.domain.empty();
  while (int(levels_.size()) < kPyramidMaxLevels) {
    const PyramidLevel& prev = levels_.back();
    const double target = finest * double(1 << levels_.size());
    PyramidLevel next = prev;
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      next.decimated[a] = false;
      if (2 * prev.frame.spacing[a] > target * (1 + 1e-6)) continue;
      if (boxed && floor_div2(inner_hi[a]) - ceil_div2(inner_lo[a]) + 1 < kPyramidMinSamples)
        continue;
      next.decimated[a] = any = true;
    }
    if (!any) break;
    for (int a = 0; a < 3; ++a) {
      if (!next.decimated[a]) continue;
      next.factor[a] *= 2;
      next.frame.spacing[a] *= 2;
      for (int r = 0; r < 3; ++r) next.frame.A(r, a) *= 2;
      if (boxed) {
        inner_lo[a] = ceil_div2(inner_lo[a]), inner_hi[a] = floor_div2(inner_hi[a]);
        // Past a clamped box the finer level is constant along the axis, so this level is too
        // from the first sample whose taps all lie past it: its box extends to that sample and
        // reads clamp there, exactly as level 0's extension (each pass clamping its own axis)
        // smoothed would give.
        next.frame.lo[a] = ceil_div2(prev.frame.lo[a] - radius) - 1;
        next.frame.hi[a] = floor_div2(prev.frame.hi[a] + radius) + 1;
      }
      next.variance[a] = (prev.variance[a] + kPyramidVariance) / 4;
    }
    next.frame.B = next.frame.A.inverse();
    next.grid = openvdb::FloatGrid::create(volume.grid->background());
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m(c, r) = next.frame.A(r, c);  // OpenVDB: row vectors
    for (int r = 0; r < 3; ++r) m(3, r) = next.frame.origin[r];
    next.grid->setTransform(openvdb::math::Transform::createLinearTransform(m));
    levels_.push_back(next);
  }
  built_.resize(levels_.size());
}

int Pyramid::level_for(double sigma) const {
  int best = 0;
  for (int k = 1; k < levels(); ++k) {
    const PyramidLevel& l = levels_[std::size_t(k)];
    bool fits = true;
    for (int a = 0; a < 3; ++a)
      if (l.factor[a] > 1 && sigma < kPyramidVoxels * l.frame.spacing[a] * (1 - 1e-9)) fits = false;
    if (fits) best = k;
  }
  return best;
}

double Pyramid::upper_scale(int k) const {
  if (k + 1 >= levels()) return std::numeric_limits<double>::infinity();
  const PyramidLevel& l = levels_[std::size_t(k + 1)];
  double s = 0;
  for (int a = 0; a < 3; ++a)
    if (l.factor[a] > 1) s = std::max(s, kPyramidVoxels * l.frame.spacing[a]);
  return s;
}

double Pyramid::max_scale() const {
  // A larger scale only moves to a coarser level; the last level's finest axis bounds it.
  const GridFrame& f = levels_.back().frame;
  return kMaxPrefilterDeviation * std::min({f.spacing[0], f.spacing[1], f.spacing[2]});
}

namespace {

/// PyramidLease's kept pyramid (one for the process) and what it was made of.
struct KeptPyramid {
  std::mutex mutex;
  std::unique_ptr<Pyramid> pyramid;
  std::weak_ptr<const openvdb::FloatGrid> grid;
  openvdb::CoordBBox domain;
};

KeptPyramid& kept_pyramid() {
  static KeptPyramid kept;
  return kept;
}

}  // namespace

PyramidLease::PyramidLease(const Volume& volume) : grid_(volume.grid), domain_(volume.domain) {
  {
    KeptPyramid& kept = kept_pyramid();
    std::lock_guard<std::mutex> lock(kept.mutex);
    // An expired grid locks to null, never equal to a live one (even at the same address).
    const bool same_grid = kept.grid.lock() == volume.grid;
    if (kept.pyramid && same_grid && kept.domain == volume.domain) {
      pyramid_ = std::move(kept.pyramid);
      pyramid_->rebind(volume.grid);
      reused_ = true;
    } else if (!same_grid) {
      kept.pyramid.reset();  // another volume now: the old one's levels go
    }
  }
  if (!pyramid_) pyramid_ = std::make_unique<Pyramid>(volume);
}

PyramidLease::~PyramidLease() {
  if (!pyramid_) return;
  pyramid_->unbind();
  if (pyramid_->built_bricks() > kKeptPyramidBricks) return;
  KeptPyramid& kept = kept_pyramid();
  std::lock_guard<std::mutex> lock(kept.mutex);
  kept.pyramid = std::move(pyramid_);
  kept.grid = grid_;
  kept.domain = domain_;
}

std::size_t Pyramid::built_bricks() const {
  std::size_t n = 0;
  for (const auto& set : built_) n += set.size();
  return n;
}

void Pyramid::build(int k, const std::vector<openvdb::Coord>& bricks) {
  if (k <= 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  build_locked(k, bricks);
}

void Pyramid::build_locked(int k, const std::vector<openvdb::Coord>& bricks) {
  PyramidLevel& level = levels_[std::size_t(k)];
  const PyramidLevel& parent = levels_[std::size_t(k - 1)];
  auto& built = built_[std::size_t(k)];
  // The bricks not built yet, those outside a dense domain left out (never read: reads clamp).
  std::vector<openvdb::Coord> todo;
  {
    std::unordered_set<openvdb::Coord, CoordHash> seen;
    for (const openvdb::Coord& b : bricks) {
      bool outside = false;
      if (level.frame.clamp)
        for (int a = 0; a < 3; ++a)
          outside = outside || 8 * b[a] + 7 < level.frame.lo[a] || 8 * b[a] > level.frame.hi[a];
      if (!outside && !built.count(b) && seen.insert(b).second) todo.push_back(b);
    }
  }
  if (todo.empty()) return;
  const int radius = decimation_radius_;
  const float* const w = decimation_.data();
  // A parent coordinate along axis a as read: clamped into a dense parent's box.
  auto read_at = [&](int v, int a) {
    return parent.frame.clamp ? std::clamp(v, parent.frame.lo[a], parent.frame.hi[a]) : v;
  };
  // The parent's bricks they read, built first.
  auto span = [&](const openvdb::Coord& b, int a) {
    const Span s = parent_span(b[a], level.decimated[a], radius);
    return Span{read_at(s.lo, a), read_at(s.hi, a)};
  };
  if (k > 1) {
    std::unordered_set<openvdb::Coord, CoordHash> need;
    for (const openvdb::Coord& b : todo) {
      const Span x = span(b, 0), y = span(b, 1), z = span(b, 2);
      for (int cz = floor_div8(z.lo); cz <= floor_div8(z.hi); ++cz)
        for (int cy = floor_div8(y.lo); cy <= floor_div8(y.hi); ++cy)
          for (int cx = floor_div8(x.lo); cx <= floor_div8(x.hi); ++cx) need.insert({cx, cy, cz});
    }
    build_locked(k - 1, std::vector<openvdb::Coord>(need.begin(), need.end()));
  }
  std::vector<float> out(todo.size() * 512);
  const openvdb::FloatGrid& from = *parent.grid;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 4), [&](const auto& r) {
    openvdb::FloatGrid::ConstAccessor acc = from.getConstAccessor();
    std::vector<float> box, pass1, pass2, scratch;
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const openvdb::Coord b = todo[i];
      // The input box (unclamped spans), read at clamped coordinates through a table of the
      // parent's leaves.
      Span s[3];
      int n[3];
      for (int a = 0; a < 3; ++a) {
        s[a] = parent_span(b[a], level.decimated[a], radius);
        n[a] = s[a].hi - s[a].lo + 1;
      }
      std::vector<int> src[3];
      for (int a = 0; a < 3; ++a) {
        src[a].resize(std::size_t(n[a]));
        for (int t = 0; t < n[a]; ++t) src[a][std::size_t(t)] = read_at(s[a].lo + t, a);
      }
      const int c0[3] = {floor_div8(src[0].front()), floor_div8(src[1].front()),
                         floor_div8(src[2].front())};
      const int cn[3] = {floor_div8(src[0].back()) - c0[0] + 1,
                         floor_div8(src[1].back()) - c0[1] + 1,
                         floor_div8(src[2].back()) - c0[2] + 1};
      std::vector<const float*> leaves(std::size_t(cn[0] * cn[1] * cn[2]));
      std::vector<float> tiles(leaves.size());
      for (int cz = 0; cz < cn[2]; ++cz)
        for (int cy = 0; cy < cn[1]; ++cy)
          for (int cx = 0; cx < cn[0]; ++cx) {
            const openvdb::Coord o(8 * (c0[0] + cx), 8 * (c0[1] + cy), 8 * (c0[2] + cz));
            const std::size_t c = std::size_t((cz * cn[1] + cy) * cn[0] + cx);
            const auto* leaf = acc.probeConstLeaf(o);
            leaves[c] = leaf ? leaf->buffer().data() : nullptr;
            tiles[c] = leaf ? 0.0f : acc.getValue(o);
          }
      // Per axis: each box coordinate's leaf cell and its part of the in-leaf offset (an
      // OpenVDB leaf holds voxel (x, y, z) at (x * 8 + y) * 8 + z).
      std::vector<int> cell[3], offset[3];
      const int scale[3] = {64, 8, 1};
      for (int a = 0; a < 3; ++a) {
        cell[a].resize(std::size_t(n[a])), offset[a].resize(std::size_t(n[a]));
        for (int t = 0; t < n[a]; ++t) {
          const int v = src[a][std::size_t(t)];
          cell[a][std::size_t(t)] = floor_div8(v) - c0[a];
          offset[a][std::size_t(t)] = (v & 7) * scale[a];
        }
      }
      // Runs of x within one leaf cell (x's cells are non-decreasing).
      std::vector<std::array<int, 2>> runs;  // [first x, cell]
      for (int x = 0; x < n[0]; ++x)
        if (x == 0 || cell[0][std::size_t(x)] != cell[0][std::size_t(x - 1)])
          runs.push_back({x, cell[0][std::size_t(x)]});
      runs.push_back({n[0], 0});
      const int* ox = offset[0].data();
      box.resize(std::size_t(n[0]) * n[1] * n[2]);
      for (int z = 0; z < n[2]; ++z)
        for (int y = 0; y < n[1]; ++y) {
          const int cyz = (cell[2][std::size_t(z)] * cn[1] + cell[1][std::size_t(y)]) * cn[0];
          const int oyz = offset[2][std::size_t(z)] + offset[1][std::size_t(y)];
          float* row = box.data() + (std::size_t(z) * n[1] + y) * n[0];
          for (std::size_t k = 0; k + 1 < runs.size(); ++k) {
            const std::size_t c = std::size_t(cyz + runs[k][1]);
            const int from = runs[k][0], to = runs[k + 1][0];
            if (const float* leaf = leaves[c]) {
              const float* base = leaf + oyz;
              for (int x = from; x < to; ++x) row[x] = base[ox[x]];
            } else {
              std::fill(row + from, row + to, tiles[c]);
            }
          }
        }
      // The three passes, each keeping only its 8 outputs along its axis (output o of a
      // decimated axis reads box index 2 o + t with taps t = 0 .. 2 r; of a kept axis, index o):
      // along y, then z, over whole x rows (contiguous: they vectorise), then along x on the
      // 8 x 8 rows left.
      const int nx = n[0], ny = n[1], nz = n[2], taps_n = 2 * radius + 1;
      auto rows = [&](const float* in, std::ptrdiff_t step, bool decimated, float* dst) {
        // dst[o][x] (8 rows of nx) from in's rows `step` apart.
        for (int o = 0; o < 8; ++o) {
          float* d = dst + std::ptrdiff_t(o) * nx;
          if (!decimated) {
            std::copy(in + o * step, in + o * step + nx, d);
            continue;
          }
          std::fill(d, d + nx, 0.0f);
          for (int t = 0; t < taps_n; ++t) {
            const float wt = w[t];
            const float* src = in + (2 * o + t) * step;
            for (int x = 0; x < nx; ++x) d[x] += wt * src[x];
          }
        }
      };
      pass1.resize(std::size_t(nz) * 8 * nx);  // [z][8 y][x]
      for (int z = 0; z < nz; ++z)
        rows(box.data() + std::size_t(z) * ny * nx, nx, level.decimated[1],
             pass1.data() + std::size_t(z) * 8 * nx);
      pass2.resize(std::size_t(64) * nx);  // [8 z][8 y][x]
      for (int y = 0; y < 8; ++y) {
        // Rows (z, y) for z = 0 .. nz - 1 are 8 nx apart in pass1; the outputs (o, y) 8 nx
        // apart in pass2: filter into a scratch of 8 rows, then place them.
        scratch.resize(std::size_t(8) * nx);
        float* tmp = scratch.data();
        rows(pass1.data() + std::size_t(y) * nx, std::ptrdiff_t(8) * nx, level.decimated[2], tmp);
        for (int o = 0; o < 8; ++o)
          std::copy(tmp + o * nx, tmp + (o + 1) * nx, pass2.data() + (std::size_t(o) * 8 + y) * nx);
      }
      float* dst = out.data() + i * 512;  // x fastest: (z * 8 + y) * 8 + x
      for (int r = 0; r < 64; ++r) {
        const float* in = pass2.data() + std::size_t(r) * nx;
        for (int o = 0; o < 8; ++o) {
          if (!level.decimated[0]) {
            dst[r * 8 + o] = in[o];
            continue;
          }
          float sum = 0;
          for (int t = 0; t < taps_n; ++t) sum += w[t] * in[2 * o + t];
          dst[r * 8 + o] = sum;
        }
      }
    }
  });
  // The new leaves made one by one (the tree is not thread-safe), then filled in parallel.
  openvdb::FloatTree& tree = level.grid->tree();
  std::vector<openvdb::FloatTree::LeafNodeType*> leaves(todo.size());
  for (std::size_t i = 0; i < todo.size(); ++i) {
    leaves[i] = tree.touchLeaf(openvdb::Coord(8 * todo[i][0], 8 * todo[i][1], 8 * todo[i][2]));
    built.insert(todo[i]);
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, todo.size(), 16), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      float* v = leaves[i]->buffer().data();
      const float* src = out.data() + i * 512;
      for (int x = 0; x < 8; ++x)
        for (int y = 0; y < 8; ++y)
          for (int z = 0; z < 8; ++z) v[(x * 8 + y) * 8 + z] = src[(z * 8 + y) * 8 + x];
      leaves[i]->setValuesOn();
    }
  });
}

double pyramid_support(const Pyramid& pyramid, double sigma, int axis, double reach) {
  const int k = pyramid.level_for(sigma);
  const PyramidLevel& l = pyramid.level(k);
  const double h = l.frame.spacing[axis];
  const double deviation = sigma / h;
  const double own = std::max(0.0, deviation * deviation - kSplineVariance - l.variance[axis]);
  const int taps = prefilter_taps(own).radius;
  // Level k's samples within taps + reach + the B-spline's of the point, each reading the
  // decimations' taps of every finer level (kPyramidVariance's radius at each).
  const int decimation = pyramid.decimation_radius();
  const double level0 = pyramid.level(0).frame.spacing[axis];
  return (taps + kSplineReach + 1) * h + reach + decimation * (h - level0);
}

}  // namespace isocurv::volume
