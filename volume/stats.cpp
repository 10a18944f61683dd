// compute_stats: value statistics of a Volume's grid over its data domain (dense) or its active
// voxels (sparse), in two deterministic parallel passes over the leaf nodes plus the tiles.
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "volume/from_dense.h"
#include "volume/otsu.h"

namespace isocurv::volume {
namespace {

constexpr int kBins = 256;

/// Pass 1: finite range, sum and non-finite counts.
struct RangeAcc {
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double sum = 0;
  std::uint64_t finite = 0, nan = 0, inf = 0;

  void add(float v, std::uint64_t count) {
    if (std::isnan(v)) {
      nan += count;
    } else if (std::isinf(v)) {
      inf += count;
    } else {
      min = std::min(min, double(v));
      max = std::max(max, double(v));
      sum += double(v) * double(count);
      finite += count;
    }
  }
  void join(const RangeAcc& o) {
    min = std::min(min, o.min);
    max = std::max(max, o.max);
    sum += o.sum;
    finite += o.finite;
    nan += o.nan;
    inf += o.inf;
  }
};

/// Pass 2: 256 equal bins over [lo, hi]; non-finite values are skipped.
struct HistAcc {
  double lo = 0, scale = 0;
  std::vector<std::uint64_t> bins = std::vector<std::uint64_t>(kBins, 0);

  void add(float v, std::uint64_t count) {
    if (!std::isfinite(v)) return;
    const double t = (double(v) - lo) * scale;
    const int b = t <= 0 ? 0 : t >= kBins - 1 ? kBins - 1 : int(t);
    bins[std::size_t(b)] += count;
  }
  void join(const HistAcc& o) {
    for (int i = 0; i < kBins; ++i) bins[std::size_t(i)] += o.bins[std::size_t(i)];
  }
};

/// Feeds every counted value of `grid` to a copy of `init` and returns the joined result.
/// Dense mode (`active_only` false): every voxel of `domain`, with voxels not stored in any node
/// counted as the background. Sparse mode: active voxels and active tiles only.
template <class Acc>
Acc reduce_values(const openvdb::FloatGrid& grid, const openvdb::CoordBBox& domain, bool active_only,
                  const Acc& init) {
  using Tree = openvdb::FloatTree;
  using Leaf = Tree::LeafNodeType;
  const Tree& tree = grid.tree();
  openvdb::tree::LeafManager<const Tree> leaves(tree);

  struct Body {
    const openvdb::tree::LeafManager<const Tree>* leaves;
    const openvdb::CoordBBox* domain;
    bool active_only;
    Acc acc;
    std::uint64_t counted = 0;

    Body(const openvdb::tree::LeafManager<const Tree>* l, const openvdb::CoordBBox* d, bool a, const Acc& init)
        : leaves(l), domain(d), active_only(a), acc(init), empty(init) {}
    Body(Body& o, tbb::split) : leaves(o.leaves), domain(o.domain), active_only(o.active_only), acc(o.empty), empty(o.empty) {}

    void operator()(const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const Leaf& leaf = leaves->leaf(i);
        openvdb::CoordBBox box = leaf.getNodeBoundingBox();
        if (!active_only) {
          box.intersect(*domain);
          if (box.empty()) continue;
        }
        const float* data = leaf.buffer().data();
        if (box == leaf.getNodeBoundingBox()) {
          for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) {
            if (active_only && !leaf.valueMask().isOn(n)) continue;
            acc.add(data[n], 1);
            ++counted;
          }
        } else {
          for (int x = box.min().x(); x <= box.max().x(); ++x)
            for (int y = box.min().y(); y <= box.max().y(); ++y)
              for (int z = box.min().z(); z <= box.max().z(); ++z) {
                const openvdb::Index n = Leaf::coordToOffset(openvdb::Coord(x, y, z));
                if (active_only && !leaf.valueMask().isOn(n)) continue;
                acc.add(data[n], 1);
                ++counted;
              }
        }
      }
    }
    void join(Body& o) {
      acc.join(o.acc);
      counted += o.counted;
    }
    Acc empty;  ///< the initial accumulator, copied into each split body
  };

  Body root(&leaves, &domain, active_only, init);
  tbb::parallel_deterministic_reduce(tbb::blocked_range<std::size_t>(0, leaves.leafCount(), 16), root);
  Acc acc = root.acc;
  std::uint64_t counted = root.counted;

  // Tiles above the leaf level (a few, visited serially in tree order).
  Tree::ValueAllCIter it = tree.cbeginValueAll();
  it.setMaxDepth(Tree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; it; ++it) {
    if (active_only && !it.isValueOn()) continue;
    openvdb::CoordBBox box = it.getBoundingBox();
    if (!active_only) box.intersect(domain);
    if (box.empty()) continue;
    acc.add(*it, box.volume());
    counted += box.volume();
  }
  // Voxels of the domain outside every node hold the background.
  if (!active_only && domain.volume() > counted) acc.add(grid.background(), domain.volume() - counted);
  return acc;
}

/// One count per integer value lo, lo + 1, ..., lo + n - 1; `other` counts any finite value that
/// is not one of them (then the values are not integers after all).
struct IntCountAcc {
  double lo = 0;
  std::vector<std::uint64_t> counts;
  std::uint64_t other = 0;
  void add(float v, std::uint64_t count) {
    if (!std::isfinite(v)) return;
    const double k = double(v) - lo;
    if (k >= 0 && k < double(counts.size()) && k == std::floor(k))
      counts[std::size_t(k)] += count;
    else
      other += count;
  }
  void join(const IntCountAcc& o) {
    for (std::size_t i = 0; i < counts.size(); ++i) counts[i] += o.counts[i];
    other += o.other;
  }
};

constexpr double kMaxExactValues = 1 << 20;

}  // namespace

std::vector<double> exact_integer_percentiles(const Volume& v, const std::vector<double>& fractions) {
  const ValueStats& s = v.stats;
  if (!v.grid || !is_integer_type(v.voxel_type) || !(s.max >= s.min) || s.min != std::floor(s.min) ||
      s.max - s.min + 1 > kMaxExactValues)
    return {};
  IntCountAcc init;
  init.lo = s.min;
  init.counts.assign(std::size_t(s.max - s.min + 1), 0);
  const IntCountAcc c = reduce_values(*v.grid, v.domain, !v.dense, init);
  std::uint64_t total = 0;
  for (std::uint64_t n : c.counts) total += n;
  if (c.other > 0 || total == 0) return {};
  std::vector<double> out;
  for (double f : fractions) {
    const double want = f * double(total);
    std::uint64_t below = 0;
    std::size_t i = 0;
    while (i + 1 < c.counts.size() && (c.counts[i] == 0 || double(below + c.counts[i]) < want)) below += c.counts[i++];
    out.push_back(s.min + double(i));
  }
  return out;
}

void compute_stats(Volume& v) {
  ValueStats s;
  const bool active_only = !v.dense;
  const openvdb::CoordBBox domain = v.domain;
  if (!v.grid || (!active_only && domain.empty())) {
    v.stats = s;
    return;
  }
  const RangeAcc range = reduce_values(*v.grid, domain, active_only, RangeAcc{});
  s.voxels = range.finite + range.nan + range.inf;
  s.nan_count = range.nan;
  s.inf_count = range.inf;
  s.histogram.assign(kBins, 0);
  if (range.finite > 0) {
    s.min = range.min;
    s.max = range.max;
    s.mean = range.sum / double(range.finite);
    HistAcc h;
    h.lo = s.min;
    h.scale = s.max > s.min ? kBins / (s.max - s.min) : 0;
    s.histogram = reduce_values(*v.grid, domain, active_only, h).bins;
  }
  const bool level_set = v.grid_class == "level set" || v.grid->getGridClass() == openvdb::GRID_LEVEL_SET;
  s.suggested_isovalue = level_set ? 0.0 : otsu_threshold(s.histogram, s.min, s.max);
  s.suggested_from = level_set ? "level set zero" : "Otsu";
  v.stats = std::move(s);
}

}  // namespace isocurv::volume
