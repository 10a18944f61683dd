#include "volume/noise_estimate.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

namespace isocurv::volume {

NoiseEstimate estimate_noise(const openvdb::FloatGrid& grid, const GridFrame& frame,
                             const Positions& points, float isovalue, std::size_t max_blocks,
                             const SurfacePiece* piece) {
  NoiseEstimate out;
  std::set<openvdb::Coord> blocks;  // ordered: deterministic
  for (const Vec3f& p : points) {
    const openvdb::Vec3d q = frame.to_index(openvdb::Vec3d(p[0], p[1], p[2]));
    const openvdb::Coord c = openvdb::Coord::floor(q);
    blocks.insert(openvdb::Coord(c[0] & ~7, c[1] & ~7, c[2] & ~7));
  }
  if (piece) {  // every piece's blocks (coordinates are exact in doubles)
    std::vector<double> mine;
    for (const openvdb::Coord& b : blocks) mine.insert(mine.end(), {double(b[0]), double(b[1]), double(b[2])});
    const std::vector<double> every = piece->all(mine);
    for (std::size_t i = 0; i + 2 < every.size(); i += 3)
      blocks.insert(openvdb::Coord(int(every[i]), int(every[i + 1]), int(every[i + 2])));
  }
  std::vector<openvdb::Coord> chosen(blocks.begin(), blocks.end());
  if (chosen.size() > max_blocks) {
    std::vector<openvdb::Coord> even;
    for (std::size_t k = 0; k < max_blocks; ++k)
      even.push_back(chosen[k * chosen.size() / max_blocks]);
    chosen.swap(even);
  }
  const int m = kNoiseEdgeDistance;
  openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
  std::vector<double> residuals;
  for (const openvdb::Coord& base : chosen) {
    if (piece && !piece->holds_cells_at(base[2])) continue;  // another piece measures it
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const openvdb::Coord c = base + openvdb::Coord(x, y, z);
          if (frame.clamp) {
            bool inner = true;
            for (int a = 0; a < 3; ++a)
              inner = inner && c[a] - m >= frame.lo[a] && c[a] + m <= frame.hi[a];
            if (!inner) continue;
          }
          const double v = acc.getValue(c);
          const bool above = v > isovalue;
          bool near_edge = false, finite = std::isfinite(v);
          // The fourth differences along the three axes, summed: blind to any cubic, so the
          // field's own smooth structure (a distance field's curvature) does not count as noise.
          double residual = 18 * v;
          for (int a = 0; a < 3 && !near_edge; ++a)
            for (int d = 1; d <= m && !near_edge; ++d)
              for (int sgn = -1; sgn <= 1; sgn += 2) {
                openvdb::Coord n = c;
                n[a] += sgn * d;
                const double w = acc.getValue(n);
                finite = finite && std::isfinite(w);
                if ((w > isovalue) != above) near_edge = true;
                if (d == 1) residual -= 4 * w;
                if (d == 2) residual += w;
              }
          if (near_edge || !finite) continue;
          residuals.push_back(residual);
        }
  }
  if (piece) residuals = piece->all(residuals);  // the median is the same in any order
  out.voxels = residuals.size();
  if (residuals.empty()) return out;
  auto median = [](std::vector<double>& r) {
    auto mid = r.begin() + r.size() / 2;
    std::nth_element(r.begin(), mid, r.end());
    return *mid;
  };
  const double med = median(residuals);
  for (double& r : residuals) r = std::abs(r - med);
  out.sigma = 1.4826 * median(residuals) / std::sqrt(kFourthDifferenceVariance);
  return out;
}

}  // namespace isocurv::volume
