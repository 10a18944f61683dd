#include "dist/slabs.h"

#include <algorithm>
#include <climits>
#include <numeric>

#include "core/error.h"

namespace isocurv::dist {

int Slabs::owner_of_cell(int z) const {
  // The last cut at or below z (cuts[0] is INT_MIN); among equal cuts (empty slabs) the last.
  const auto it = std::upper_bound(cuts.begin() + 1, cuts.end() - 1, z);
  return int(it - cuts.begin()) - 1;
}

int Slabs::owner_of_key(std::uint64_t key) const {
  const int z = int((key >> 2) & 0xfffffu) + key_origin_z;
  return owner_of_cell(z);
}

std::pair<int, int> Slabs::extract_range(int r, int margin) const {
  const long long lo = cuts[r] == INT_MIN ? INT_MIN : (long long)cuts[r] - margin;
  const long long hi = cuts[r + 1] == INT_MAX ? INT_MAX : (long long)cuts[r + 1] - 1 + margin;
  return {int(std::max<long long>(lo, INT_MIN)), int(std::min<long long>(hi, INT_MAX))};
}

LayerBricks count_layer_bricks(int cells_min_z, int cells_max_z, const std::vector<int>& brick_z, int count_from,
                               int count_to) {
  LayerBricks r;
  if (cells_min_z > cells_max_z) return r;
  r.first_layer_z = cells_min_z & ~7;
  r.counts.assign(std::size_t((cells_max_z - r.first_layer_z) / 8 + 1), 0);
  for (int z : brick_z)
    if (z >= count_from && z <= count_to && z >= r.first_layer_z && (z - r.first_layer_z) / 8 < int(r.counts.size()))
      ++r.counts[std::size_t((z - r.first_layer_z) / 8)];
  return r;
}

std::vector<std::uint64_t> read_in_part_costs(const std::vector<std::uint64_t>& surface_bricks,
                                              const std::vector<std::uint64_t>& leaves,
                                              std::uint64_t blocks_per_layer) {
  std::vector<std::uint64_t> cost(surface_bricks.size());
  for (std::size_t i = 0; i < cost.size(); ++i)
    cost[i] = surface_bricks[i] * kSurfaceBrickCost + blocks_per_layer * kBlockReadCost +
              (i < leaves.size() ? leaves[i] : 0) * kLeafBuildCost;
  return cost;
}

Slabs balance_slabs(const std::vector<std::uint64_t>& layer_bricks, int first_layer_z, int ranks,
                    int key_origin_z) {
  if (ranks < 1) throw Error("balance_slabs: at least one rank");
  Slabs s;
  s.key_origin_z = key_origin_z;
  s.cuts.assign(std::size_t(ranks) + 1, INT_MIN);
  s.cuts.back() = INT_MAX;
  const long double total = std::accumulate(layer_bricks.begin(), layer_bricks.end(), 0.0L);
  std::size_t layer = 0;
  long double running = 0;
  for (int r = 1; r < ranks; ++r) {
    const long double target = total * r / ranks;
    while (layer < layer_bricks.size() && running + layer_bricks[layer] / 2.0L <= target)
      running += layer_bricks[layer++];
    s.cuts[r] = first_layer_z + 8 * int(layer);
  }
  return s;
}

}  // namespace isocurv::dist
