#include "dist/volume_stats.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "volume/otsu.h"

namespace isocurv::dist {
namespace {

constexpr int kBins = 256;  // volume::ValueStats::histogram

// The histogram of `v`'s finite values in its slab over [lo, hi], binned as the loader bins
// (volume/from_dense.cpp): the grid holds non-finite voxels as its outside value, so they are
// counted there and taken out again.
std::vector<std::uint64_t> slab_histogram(const volume::Volume& v, double lo, double hi) {
  const openvdb::CoordBBox box = v.slab ? *v.slab : v.domain;
  const double scale = hi > lo ? kBins / (hi - lo) : 0.0;
  auto bin = [&](float value) {
    const double t = (double(value) - lo) * scale;
    return std::size_t(t <= 0 ? 0 : t >= kBins - 1 ? kBins - 1 : int(t));
  };
  using Hist = std::vector<std::uint64_t>;
  Hist h = tbb::parallel_reduce(
      tbb::blocked_range<int>(box.min().z(), box.max().z() + 1), Hist(kBins, 0),
      [&](const tbb::blocked_range<int>& r, Hist acc) {
        openvdb::FloatGrid::ConstAccessor a = v.grid->getConstAccessor();
        for (int z = r.begin(); z != r.end(); ++z)
          for (int y = box.min().y(); y <= box.max().y(); ++y)
            for (int x = box.min().x(); x <= box.max().x(); ++x) ++acc[bin(a.getValue(openvdb::Coord(x, y, z)))];
        return acc;
      },
      [](Hist a, const Hist& b) {
        for (int i = 0; i < kBins; ++i) a[std::size_t(i)] += b[std::size_t(i)];
        return a;
      });
  h[bin(v.grid->background())] -= v.stats.nan_count + v.stats.inf_count;
  return h;
}

}  // namespace

volume::ValueStats reduce_stats(const World& world, const volume::Volume* share, const std::string& path) {
  volume::ValueStats none;
  none.min = std::numeric_limits<double>::infinity();
  none.max = -std::numeric_limits<double>::infinity();
  const volume::ValueStats& s = share ? share->stats : none;
  const std::uint64_t finite = s.voxels - s.nan_count - s.inf_count;
  const std::vector<double> range = world.max({-s.min, s.max});
  const std::vector<std::int64_t> counts =
      world.sum(std::vector<std::int64_t>{std::int64_t(s.voxels), std::int64_t(s.nan_count),
                                          std::int64_t(s.inf_count), std::int64_t(finite)});
  const std::vector<double> sums = world.sum(std::vector<double>{s.mean * double(finite)});
  volume::ValueStats out;
  out.min = -range[0];
  out.max = range[1];
  out.voxels = std::uint64_t(counts[0]);
  out.nan_count = std::uint64_t(counts[1]);
  out.inf_count = std::uint64_t(counts[2]);
  if (counts[3] == 0) throw Error(path, "all " + std::to_string(counts[0]) + " voxels are NaN or Inf");
  out.mean = sums[0] / double(counts[3]);
  const std::vector<std::uint64_t> mine =
      share ? slab_histogram(*share, out.min, out.max) : std::vector<std::uint64_t>(kBins, 0);
  const std::vector<std::int64_t> total = world.sum(std::vector<std::int64_t>(mine.begin(), mine.end()));
  out.histogram.assign(total.begin(), total.end());
  out.suggested_isovalue = volume::otsu_threshold(out.histogram, out.min, out.max);
  return out;
}

}  // namespace isocurv::dist
