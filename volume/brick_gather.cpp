#include "volume/brick_gather.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace isocurv::volume {
namespace {

int floor_div8(int v) { return v >= 0 ? v / 8 : -((-v + 7) / 8); }

}  // namespace

BrickGather gather_bricks(const openvdb::FloatGrid& grid, const GridFrame& frame,
                          const Positions& world_points, const openvdb::Vec3d& reach) {
  BrickGather out;
  if (world_points.empty()) return out;
  // Each point's window as a box of bricks.
  const std::size_t n = world_points.size();
  std::vector<openvdb::CoordBBox> boxes(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3f& p = world_points[i];
      const openvdb::Vec3d q = frame.to_index(openvdb::Vec3d(p[0], p[1], p[2]));
      openvdb::Coord lo, hi;
      for (int a = 0; a < 3; ++a) {
        double l = std::floor(q[a] - reach[a]), h = std::ceil(q[a] + reach[a]);
        if (frame.clamp) {
          l = std::clamp(l, double(frame.lo[a]), double(frame.hi[a]));
          h = std::clamp(h, double(frame.lo[a]), double(frame.hi[a]));
        }
        l = std::clamp(l, -1e9, 1e9), h = std::clamp(h, -1e9, 1e9);
        lo[a] = floor_div8(int(l));
        hi[a] = floor_div8(int(h));
      }
      boxes[i] = openvdb::CoordBBox(lo, hi);
    }
  });
  openvdb::CoordBBox all = boxes[0];
  for (const openvdb::CoordBBox& b : boxes) all.expand(b);
  const openvdb::Coord dims = all.dim();
  const double cells = double(dims[0]) * dims[1] * dims[2];
  if (cells > double(std::numeric_limits<std::int32_t>::max()))
    throw Error("volume: the surface's filter windows span too large a region");
  out.origin = openvdb::Coord(all.min()[0] * 8, all.min()[1] * 8, all.min()[2] * 8);
  out.dims = dims;
  out.table.assign(std::size_t(cells), -1);
  auto cell = [&](const openvdb::Coord& b) {
    const openvdb::Coord r = b - all.min();
    return (std::size_t(r[2]) * dims[1] + r[1]) * dims[0] + r[0];
  };
  for (const openvdb::CoordBBox& b : boxes)
    for (int z = b.min()[2]; z <= b.max()[2]; ++z)
      for (int y = b.min()[1]; y <= b.max()[1]; ++y)
        for (int x = b.min()[0]; x <= b.max()[0]; ++x) out.table[cell({x, y, z})] = 0;
  // Number the bricks in table order (deterministic), then fill them in parallel.
  std::vector<openvdb::Coord> bricks;
  std::int32_t next = 0;
  for (std::size_t c = 0; c < out.table.size(); ++c)
    if (out.table[c] == 0) {
      out.table[c] = next++;
      const std::size_t x = c % dims[0], y = (c / dims[0]) % dims[1],
                        z = c / (std::size_t(dims[0]) * dims[1]);
      bricks.push_back(all.min() + openvdb::Coord(int(x), int(y), int(z)));
    }
  out.samples.resize(bricks.size() * 512);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bricks.size(), 16), [&](const auto& r) {
    openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      const openvdb::Coord base(bricks[b][0] * 8, bricks[b][1] * 8, bricks[b][2] * 8);
      float* dst = out.samples.data() + b * 512;
      for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
          for (int x = 0; x < 8; ++x)
            dst[(z * 8 + y) * 8 + x] = acc.getValue(base + openvdb::Coord(x, y, z));
    }
  });
  return out;
}

}  // namespace isocurv::volume
