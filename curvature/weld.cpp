#include "curvature/weld.h"

#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

namespace isocurv::curvature {
namespace {

struct Key {
  std::uint32_t bits[3];
  bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
};

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    return (std::size_t(k.bits[0]) * 73856093u) ^ (std::size_t(k.bits[1]) * 19349663u) ^
           (std::size_t(k.bits[2]) * 83492791u);
  }
};

}  // namespace

std::size_t weld_duplicates(Mesh& mesh) {
  const std::size_t nv = mesh.positions.size();
  std::unordered_map<Key, std::uint32_t, KeyHash> first;
  first.reserve(nv);
  std::vector<std::uint32_t> to(nv);
  Positions kept;
  kept.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec3f& p = mesh.positions[i];
    if (p[0] != p[0] || p[1] != p[1] || p[2] != p[2]) {  // NaN: never equal to anything
      to[i] = std::uint32_t(kept.size());
      kept.push_back(p);
      continue;
    }
    Key k;
    const float c[3] = {p[0] + 0.0f, p[1] + 0.0f, p[2] + 0.0f};  // -0 -> +0
    std::memcpy(k.bits, c, sizeof k.bits);
    const auto [it, fresh] = first.emplace(k, std::uint32_t(kept.size()));
    if (fresh) kept.push_back(p);
    to[i] = it->second;
  }
  const std::size_t removed = nv - kept.size();
  if (removed == 0) return 0;
  for (Tri& t : mesh.triangles)
    for (std::uint32_t& i : t)
      if (i < nv) i = to[i];
  mesh.positions = std::move(kept);
  mesh.edge_keys.clear();
  return removed;
}

}  // namespace isocurv::curvature
