#include "core/union_find.h"
#include "core/vec3.h"
#include "mc/snap_vertices.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace isocurv::mc {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr std::uint64_t kField = 0xfffff;  // one coordinate of an edge key (20 bits)

using Vec3d = std::array<double, 3>;

using vec3::to_double;
using vec3::sub;
using vec3::cross;
using vec3::dot;

// Twice the area vector of the triangle (a, b, c).
Vec3d area_vector(const Vec3d& a, const Vec3d& b, const Vec3d& c) { return cross(sub(b, a), sub(c, a)); }

// The key-space coordinates of the voxel a candidate snaps to, as one sortable number (an edge
// key's layout with the axis bits clear).
std::uint64_t point_key(std::uint64_t edge) {
  std::uint64_t x = (edge >> 42) & kField, y = (edge >> 22) & kField, z = (edge >> 2) & kField;
  if (edge & kSnapUpper) {
    const int axis = static_cast<int>(edge & 3u);
    (axis == 0 ? x : axis == 1 ? y : z) += 1;
  }
  return (x << 42) | (y << 22) | (z << 2);
}

// The frame's world -> index map: index = inverse (world - translation), in double. Snapping
// judges every triangle in index space, so its decisions do not depend on the spacing.
struct IndexMap {
  double inv[3][3];
  double t[3];
  explicit IndexMap(const Frame& f) {
    const auto& w = f.world;
    const double a[3][3] = {{w[0], w[1], w[2]}, {w[4], w[5], w[6]}, {w[8], w[9], w[10]}};
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        // inverse = adjugate / det: cofactor of (c, r)
        const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
        inv[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / det;
      }
    for (int r = 0; r < 3; ++r) t[r] = w[r * 4 + 3];
  }
  // Exact for the identity map (spacing 1, origin 0): the world positions themselves.
  Vec3d operator()(const Vec3d& p) const {
    const double d[3] = {p[0] - t[0], p[1] - t[1], p[2] - t[2]};
    Vec3d i;
    for (int r = 0; r < 3; ++r) i[r] = inv[r][0] * d[0] + inv[r][1] * d[1] + inv[r][2] * d[2];
    return i;
  }
  Vec3d operator()(const Vec3f& p) const { return (*this)(to_double(p)); }
};

// Index position of the voxel with point key `p` (signed sums: key origins, and so voxels, may
// lie at negative index coordinates).
Vec3d voxel_index(std::uint64_t p, const Frame& f) {
  return {double(std::int64_t((p >> 42) & kField) + f.key_origin.x()),
          double(std::int64_t((p >> 22) & kField) + f.key_origin.y()),
          double(std::int64_t((p >> 2) & kField) + f.key_origin.z())};
}

// The world position of index position `i` (the frame's map, in double).
Vec3d world_of(const Vec3d& i, const Frame& f) {
  Vec3d w;
  for (int r = 0; r < 3; ++r)
    w[r] = f.world[r * 4 + 0] * i[0] + f.world[r * 4 + 1] * i[1] + f.world[r * 4 + 2] * i[2] +
           f.world[r * 4 + 3];
  return w;
}

// World position of the voxel with point key `p`, computed as the reference mesher places
// vertices (double sums of the float map).
Vec3d voxel_position(std::uint64_t p, const Frame& f) { return world_of(voxel_index(p, f), f); }

// Where a voxel's surface splits into several fans (sheets touching there, or a tunnel pinched
// to a point), each fan's vertex sits this far (in voxels) from the voxel towards its own fan,
// so no two vertices coincide.
constexpr double kFanOffset = 2.0 / 1024.0;

// Passes over the voxels refused in the previous pass.
constexpr int kSnapRounds = 3;

// The parity class (x & 1, y & 1, z & 1) of a point key's voxel, 0..7.
int parity(std::uint64_t p) {
  return int(((p >> 42) & 1u) | (((p >> 22) & 1u) << 1) | (((p >> 2) & 1u) << 2));
}

// A triangle of a group's star that keeps one member: (m, a, b) in winding order.
struct Kept {
  std::uint32_t tri, m, a, b;
  int partner_a = -1, partner_b = -1;  // the kept triangle across spoke (voxel, a) / (voxel, b)
  int twin = -1;  // the kept triangle it cancels with (the same two outer vertices, other winding)
};

// One thread's working arrays (kept between voxels) and its share of the report.
struct Worker {
  std::vector<std::uint32_t> vertices, tris, dropped, kept_tris, order;
  std::vector<Vec3f> outer;
  std::vector<Kept> kept;
  UnionFind fans{0};  // kept triangles joined across spokes
  std::vector<int> fan_of, root_fan, size, open;
  std::vector<Vec3f> where_f;
  SnapReport report;
};

// The pass's working state: the mesh being edited, the candidates sorted by voxel and edge, and
// for each candidate the triangles using it.
class Snapper {
 public:
  Snapper(Mesh& mesh, const std::vector<SnapCandidate>& c, const Frame& frame, double min_area)
      : mesh_(mesh), cand_(c), frame_(frame), index_(frame), min_area_(min_area) {
    slot_.assign(mesh.positions.size(), kNone);
    for (std::uint32_t i = 0; i < cand_.size(); ++i) slot_[cand_[i].vertex] = i;
    // The triangles with a candidate (one parallel scan in fixed chunks, joined in order), and
    // their incidence lists (compressed rows).
    const Triangles& all = mesh_.triangles;
    constexpr std::size_t kChunk = 16384;
    std::vector<std::vector<std::uint32_t>> found((all.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t c) {
      const std::size_t end = std::min(all.size(), (c + 1) * kChunk);
      for (std::size_t t = c * kChunk; t < end; ++t)
        if (slot_[all[t][0]] != kNone || slot_[all[t][1]] != kNone || slot_[all[t][2]] != kNone)
          found[c].push_back(static_cast<std::uint32_t>(t));
    });
    std::vector<std::uint32_t> touching;
    for (const auto& part : found) touching.insert(touching.end(), part.begin(), part.end());
    first_.assign(cand_.size() + 1, 0);
    for (std::uint32_t t : touching)
      for (std::uint32_t v : all[t])
        if (slot_[v] != kNone) ++first_[slot_[v] + 1];
    std::partial_sum(first_.begin(), first_.end(), first_.begin());
    incident_.resize(first_.back());
    std::vector<std::uint32_t> fill(first_.begin(), first_.end() - 1);
    for (std::uint32_t t : touching)
      for (std::uint32_t v : all[t])
        if (slot_[v] != kNone) incident_[fill[slot_[v]]++] = t;
  }

  // Snaps the candidates [b, e), which all lie near the voxel `point`: every triangle with two or
  // more of them collapses; the others form fans around the voxel (triangles joined across each
  // spoke as they were joined around its outer vertex, through the collapsed ones); one fan puts
  // its vertex on the voxel, several each put theirs a little towards their own fan.
  bool snap_group(std::uint32_t b, std::uint32_t e, std::uint64_t point, Worker& w) {
    // Membership by the group's few vertex numbers (a scan of a handful, in cache; the per-vertex
    // slot table is large and read at random).
    std::vector<std::uint32_t>& vertices = w.vertices;
    vertices.clear();
    for (std::uint32_t i = b; i < e; ++i) vertices.push_back(cand_[i].vertex);
    auto member = [&](std::uint32_t v) {
      return std::find(vertices.begin(), vertices.end(), v) != vertices.end();
    };
    std::vector<std::uint32_t>& tris = w.tris;
    tris.clear();
    for (std::uint32_t i = b; i < e; ++i)
      for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k)
        if (mesh_.triangles[incident_[k]][0] != kNone) tris.push_back(incident_[k]);
    std::sort(tris.begin(), tris.end());
    tris.erase(std::unique(tris.begin(), tris.end()), tris.end());

    std::vector<Kept>& kept = w.kept;
    std::vector<std::uint32_t>& dropped = w.dropped;
    kept.clear();
    dropped.clear();
    for (std::uint32_t t : tris) {
      const Tri& tri = mesh_.triangles[t];
      int n = 0, r = 0;
      for (int k = 0; k < 3; ++k)
        if (member(tri[k])) {
          ++n;
          r = k;
        }
      if (n > 1) {
        dropped.push_back(t);
      } else {
        kept.push_back({t, tri[r], tri[(r + 1) % 3], tri[(r + 2) % 3]});
      }
    }
    const std::uint32_t members = e - b;
    if (!cancel_folds(kept, w)) return false;
    const bool none_left =
        std::all_of(kept.begin(), kept.end(), [](const Kept& k) { return k.twin >= 0; });
    if (none_left) {  // a closed speck around the voxel: it vanishes
      for (const Kept& k : kept) dropped.push_back(k.tri);
      for (std::uint32_t t : dropped) mesh_.triangles[t] = {kNone, kNone, kNone};
      w.report.merged += members;
      w.report.dropped += dropped.size();
      return true;
    }
    if (!pair_spokes(kept, member, tris, w)) return false;

    // Fans: kept triangles joined across spokes.
    const int nk = static_cast<int>(kept.size());
    UnionFind& fans = w.fans;
    fans.reset(std::size_t(nk));
    for (int i = 0; i < nk; ++i)
      for (int p : {kept[i].partner_a, kept[i].partner_b})
        if (p >= 0) fans.unite(std::uint32_t(i), std::uint32_t(p));
    std::vector<int>& fan_of = w.fan_of;
    std::vector<int>& root_fan = w.root_fan;
    fan_of.assign(nk, -1);
    root_fan.assign(nk, -1);
    int nfans = 0;
    for (int i = 0; i < nk; ++i) {
      if (kept[i].twin >= 0) continue;
      int& f = root_fan[fans.find(std::uint32_t(i))];
      if (f < 0) f = nfans++;
      fan_of[i] = f;
    }
    if (!fans_are_discs(kept, fan_of, nfans, w)) return false;

    // Each fan's vertex: on the voxel, or beside it towards the fan's outer vertices.
    const Vec3d at = voxel_position(point, frame_);
    const Vec3d at_index = voxel_index(point, frame_);
    std::vector<Vec3d> where(nfans, at);
    if (nfans > 1) {
      for (int f = 0; f < nfans; ++f) {
        // The mean of the fan's outer vertices, summed in position order (not triangle order).
        std::vector<Vec3f>& outer = w.outer;
        outer.clear();
        for (int i = 0; i < nk; ++i)
          if (fan_of[i] == f) {
            outer.push_back(mesh_.positions[kept[i].a]);
            outer.push_back(mesh_.positions[kept[i].b]);
          }
        std::sort(outer.begin(), outer.end());
        Vec3d sum{0, 0, 0};
        for (const Vec3f& q : outer) {
          const Vec3d qi = index_(q);
          for (int c = 0; c < 3; ++c) sum[c] += qi[c];
        }
        const double count = double(outer.size());
        const Vec3d d = {sum[0] / count - at_index[0], sum[1] / count - at_index[1],
                         sum[2] / count - at_index[2]};
        const double len = std::sqrt(dot(d, d));
        if (!(len > 0)) return false;
        Vec3d moved;
        for (int c = 0; c < 3; ++c) moved[c] = at_index[c] + kFanOffset * d[c] / len;
        where[f] = world_of(moved, frame_);
      }
    }
    std::vector<Vec3f>& where_f = w.where_f;
    where_f.resize(nfans);
    for (int f = 0; f < nfans; ++f)
      where_f[f] = {float(where[f][0]), float(where[f][1]), float(where[f][2])};
    for (int f = 0; f < nfans; ++f)  // fans facing the same way (symmetric sheets) would coincide
      for (int g = 0; g < f; ++g) {
        const Vec3d d = sub(index_(where_f[f]), index_(where_f[g]));
        if (where_f[f] == where_f[g] || dot(d, d) < 0.25 * kFanOffset * kFanOffset) return false;
      }

    // Sound geometry: no triangle too small or turned over.
    auto sound = [&] {
      for (int i = 0; i < nk; ++i) {
        const Kept& k = kept[i];
        if (fan_of[i] < 0) continue;
        const Vec3d p = index_(where_f[fan_of[i]]);
        const Vec3d a = index_(mesh_.positions[k.a]), b = index_(mesh_.positions[k.b]);
        const Vec3d after = area_vector(p, a, b);
        const Vec3d before = area_vector(index_(mesh_.positions[k.m]), a, b);
        if (0.5 * std::sqrt(dot(after, after)) < min_area_ || dot(after, before) < 0) return false;
      }
      return true;
    };
    if (nfans == 1) {
      // A lone fan merges its vertices at their centroid: near the isosurface they all lie on,
      // where the voxel itself may lie up to the snap distance off it. On the voxel instead when
      // the centroid would leave a bad triangle.
      Vec3d sum{0, 0, 0};
      for (std::uint32_t i = b; i < e; ++i)
        for (int c = 0; c < 3; ++c) sum[c] += mesh_.positions[cand_[i].vertex][c];
      const Vec3f on_voxel = where_f[0];
      where_f[0] = {float(sum[0] / members), float(sum[1] / members), float(sum[2] / members)};
      if (!sound()) where_f[0] = on_voxel;
    }
    if (!sound()) return false;

    // Each fan keeps one of its members' vertex (and edge key): fans in the order of their new
    // positions (distinct), each taking its smallest-key member not yet taken (members are sorted
    // by key), so the choice does not depend on vertex numbering. A fan left without a member of
    // its own is refused.
    std::vector<std::uint32_t> order(nfans);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t x, std::uint32_t y) { return where_f[x] < where_f[y]; });
    std::vector<std::uint32_t> vertex_of_fan(nfans, kNone);
    std::vector<char> taken(members, 0);
    for (std::uint32_t f : order) {
      std::uint32_t best = kNone;
      for (int i = 0; i < nk; ++i)
        if (fan_of[i] == int(f) && !taken[slot_[kept[i].m] - b]) best = std::min(best, slot_[kept[i].m]);
      if (best == kNone) return false;
      taken[best - b] = 1;
      vertex_of_fan[f] = cand_[best].vertex;
    }

    // Apply.
    for (int f = 0; f < nfans; ++f) mesh_.positions[vertex_of_fan[f]] = where_f[f];
    for (const Kept& k : kept)
      if (k.twin >= 0) dropped.push_back(k.tri);
    for (std::uint32_t t : dropped) mesh_.triangles[t] = {kNone, kNone, kNone};
    for (int i = 0; i < nk; ++i)
      if (fan_of[i] >= 0) mesh_.triangles[kept[i].tri] = {vertex_of_fan[fan_of[i]], kept[i].a, kept[i].b};
    w.report.moved += static_cast<std::size_t>(nfans);
    w.report.merged += members - static_cast<std::size_t>(nfans);
    w.report.dropped += dropped.size();
    w.report.split += nfans > 1;
    return true;
  }

  // Moves the candidates [b, e) of the voxel `point`, whose merge was refused, along their own
  // cube edges away from the voxel to the fraction `push` of the edge (only outwards: one already
  // farther keeps its place). The connectivity stays as the mesher made it; the triangles between
  // the voxel's vertices grow from the mesher's 1/1024-voxel nudge to about push. Returns the
  // vertices moved: none where a triangle using them would turn over or shrink below min_area.
  std::size_t push_group(std::uint32_t b, std::uint32_t e, std::uint64_t point, double push) {
    const Vec3d at = voxel_position(point, frame_);
    const Vec3d at_index = voxel_index(point, frame_);
    std::vector<std::pair<std::uint32_t, Vec3f>> old;
    for (std::uint32_t i = b; i < e; ++i) {
      const std::uint64_t edge = cand_[i].edge;
      const std::uint64_t other = point_key((edge & kSnapUpper) ? edge & ~kSnapUpper : edge | kSnapUpper);
      const Vec3d d = sub(voxel_position(other, frame_), at);
      Vec3f& p = mesh_.positions[cand_[i].vertex];
      // How far along its edge, in index space (a unit edge).
      const Vec3d now = sub(index_(p), at_index);
      if (dot(now, now) >= push * push) continue;
      old.emplace_back(cand_[i].vertex, p);
      p = {float(at[0] + push * d[0]), float(at[1] + push * d[1]), float(at[2] + push * d[2])};
    }
    auto position_before = [&](std::uint32_t v) {
      for (const auto& [u, q] : old)
        if (u == v) return q;
      return mesh_.positions[v];
    };
    bool sound = true;
    for (std::uint32_t i = b; i < e && sound; ++i)
      for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k) {
        const Tri& t = mesh_.triangles[incident_[k]];
        if (t[0] == kNone) continue;
        const Vec3d before = area_vector(index_(position_before(t[0])), index_(position_before(t[1])),
                                         index_(position_before(t[2])));
        const Vec3d after = area_vector(index_(mesh_.positions[t[0]]), index_(mesh_.positions[t[1]]),
                                        index_(mesh_.positions[t[2]]));
        if (dot(after, before) <= 0 || 0.5 * std::sqrt(dot(after, after)) < min_area_) {
          sound = false;
          break;
        }
      }
    if (!sound)
      for (const auto& [u, q] : old) mesh_.positions[u] = q;
    return sound ? old.size() : 0;
  }

  // Removes collapsed triangles, then every vertex no triangle uses any more (those merged
  // away, and those whose every triangle collapsed), keeping the order of the rest.
  void compact(SnapReport& report) {
    Triangles& tris = mesh_.triangles;
    if (report.dropped == 0 && report.merged == 0) return;
    tris.erase(std::remove_if(tris.begin(), tris.end(), [](const Tri& t) { return t[0] == kNone; }),
               tris.end());
    const std::size_t nv = mesh_.positions.size();
    std::unique_ptr<std::atomic<std::uint8_t>[]> used(new std::atomic<std::uint8_t>[nv]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 65536),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t v = r.begin(); v != r.end(); ++v)
                          used[v].store(0, std::memory_order_relaxed);
                      });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t t = r.begin(); t != r.end(); ++t)
                          for (std::uint32_t v : tris[t]) used[v].store(1, std::memory_order_relaxed);
                      });
    std::vector<std::uint32_t> index(nv);
    std::uint32_t next = 0;
    const bool keys = mesh_.edge_keys.size() == nv;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!used[v].load(std::memory_order_relaxed)) {
        index[v] = kNone;
        continue;
      }
      index[v] = next;
      mesh_.positions[next] = mesh_.positions[v];
      if (keys) mesh_.edge_keys[next] = mesh_.edge_keys[v];
      ++next;
    }
    report.vanished = nv - next - report.merged;
    mesh_.positions.resize(next);
    if (keys) mesh_.edge_keys.resize(next);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tris.size(), 16384),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t t = r.begin(); t != r.end(); ++t)
                          for (std::uint32_t& v : tris[t]) v = index[v];
                      });
  }

 private:
  // Pairs the kept triangles that would become one triangle wound both ways (two vertices near the
  // voxel joined to the same two outer vertices from either side): such a fold cancels out. False
  // when two would become the same triangle, or three share their outer vertices.
  static bool cancel_folds(std::vector<Kept>& kept, Worker& w) {
    std::vector<std::uint32_t>& order = w.order;
    order.resize(kept.size());
    std::iota(order.begin(), order.end(), 0);
    auto pair_of = [&](std::uint32_t i) {
      return std::make_pair(std::min(kept[i].a, kept[i].b), std::max(kept[i].a, kept[i].b));
    };
    std::sort(order.begin(), order.end(),
              [&](std::uint32_t x, std::uint32_t y) { return pair_of(x) < pair_of(y); });
    for (std::size_t i = 0; i < order.size();) {
      std::size_t j = i + 1;
      while (j < order.size() && pair_of(order[j]) == pair_of(order[i])) ++j;
      if (j - i > 2) return false;
      if (j - i == 2) {
        Kept &x = kept[order[i]], &y = kept[order[i + 1]];
        if (x.a != y.b) return false;  // the same winding: a duplicate, not a fold
        x.twin = int(order[i + 1]);
        y.twin = int(order[i]);
      }
      i = j;
    }
    return true;
  }

  // Finds each kept triangle's partner across its two spokes: walking around the outer vertex a
  // from (m, a), across collapsing triangles (their spokes to other members), to the next kept
  // triangle. False when a walk does not end (a broken mesh).
  template <class Member>
  bool pair_spokes(std::vector<Kept>& kept, const Member& member, const std::vector<std::uint32_t>& tris,
                   Worker& w) {
    std::vector<std::uint32_t>& kept_tris = w.kept_tris;
    kept_tris.resize(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) kept_tris[i] = kept[i].tri;
    auto kept_index = [&](std::uint32_t t) {  // tris and kept are both in triangle order
      auto it = std::lower_bound(kept_tris.begin(), kept_tris.end(), t);
      return it != kept_tris.end() && *it == t ? int(it - kept_tris.begin()) : -1;
    };
    // The other triangle on edge (outer, m), not `from`, or kNone at a boundary.
    auto across = [&](std::uint32_t outer, std::uint32_t m, std::uint32_t from) {
      const std::uint32_t s = slot_[m];
      for (std::uint32_t k = first_[s]; k < first_[s + 1]; ++k) {
        const std::uint32_t t = incident_[k];
        const Tri& tri = mesh_.triangles[t];
        if (t != from && tri[0] != kNone && (tri[0] == outer || tri[1] == outer || tri[2] == outer)) return t;
      }
      return kNone;
    };
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (int side = 0; side < 2 && kept[i].twin < 0; ++side) {
        const std::uint32_t outer = side == 0 ? kept[i].a : kept[i].b;
        std::uint32_t from = kept[i].tri, m = kept[i].m;
        int partner = -1;
        for (std::size_t steps = 0; steps <= tris.size(); ++steps) {
          const std::uint32_t t = across(outer, m, from);
          if (t == kNone) break;  // boundary spoke
          const int k = kept_index(t);
          if (k >= 0 && kept[k].twin < 0) {
            partner = k;
            break;
          }
          if (k >= 0) {  // a cancelled fold: on through its twin, across the twin's spoke
            const Kept& w = kept[kept[k].twin];
            from = w.tri;
            m = w.m;
            continue;
          }
          // A collapsing triangle (outer, m, m2): carry on across (outer, m2).
          const Tri& tri = mesh_.triangles[t];
          std::uint32_t m2 = kNone;
          for (std::uint32_t v : tri)
            if (v != m && v != outer && member(v)) m2 = v;
          if (m2 == kNone) return false;
          from = t;
          m = m2;
          if (steps == tris.size()) return false;
        }
        (side == 0 ? kept[i].partner_a : kept[i].partner_b) = partner;
      }
    return true;
  }

  // Each fan must be one disc around its vertex: partners agree (across spoke (v, a) of one
  // triangle lies the triangle with a as its b, and that one's partner is the first), a closed fan
  // has at least three triangles, and no outer vertex is met twice in a fan (as a twice, as b
  // twice, or as a and b of two triangles that do not join there).
  static bool fans_are_discs(const std::vector<Kept>& kept, const std::vector<int>& fan_of, int nfans,
                             Worker& w) {
    std::vector<int>& size = w.size;
    std::vector<int>& open = w.open;
    size.assign(nfans, 0);
    open.assign(nfans, 0);
    const int nk = static_cast<int>(kept.size());
    for (int i = 0; i < nk; ++i) {
      const Kept& k = kept[i];
      if (fan_of[i] < 0) continue;
      if (k.partner_a >= 0 && (kept[k.partner_a].b != k.a || kept[k.partner_a].partner_b != i)) return false;
      if (k.partner_b >= 0 && (kept[k.partner_b].a != k.b || kept[k.partner_b].partner_a != i)) return false;
      ++size[fan_of[i]];
      open[fan_of[i]] += (k.partner_a < 0) + (k.partner_b < 0);
    }
    for (int f = 0; f < nfans; ++f)
      if ((open[f] != 0 && open[f] != 2) || (open[f] == 0 && size[f] < 3)) return false;
    // Pairs of one fan (a dozen triangles: a scan beats sorting).
    for (int i = 0; i < nk; ++i)
      for (int j = i + 1; j < nk; ++j) {
        if (fan_of[i] < 0 || fan_of[i] != fan_of[j]) continue;
        const Kept &x = kept[i], &y = kept[j];
        if (x.a == y.a || x.b == y.b) return false;       // the same role twice
        if (x.a == y.b && x.partner_a != j) return false;  // a and b, not joined there
        if (x.b == y.a && y.partner_a != i) return false;
      }
    return true;
  }

  Mesh& mesh_;
  const std::vector<SnapCandidate>& cand_;
  const Frame& frame_;
  IndexMap index_;                       // world -> index: every judgement is made there
  double min_area_;                      // index units (voxel faces)
  std::vector<std::uint32_t> slot_;      // per vertex: its candidate, or kNone
  std::vector<std::uint32_t> first_;     // per candidate: where its triangles start in incident_
  std::vector<std::uint32_t> incident_;  // triangles using each candidate
};

}  // namespace

SnapReport snap_vertices(Mesh& mesh, std::vector<SnapCandidate> candidates, const Frame& frame,
                         double min_area, double push) {
  SnapReport report;
  report.candidates = candidates.size();
  if (candidates.empty()) return report;
  // Voxel by voxel, members by edge key: an order that does not depend on vertex numbering.
  std::vector<std::pair<std::uint64_t, SnapCandidate>> sorted(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i)
    sorted[i] = {point_key(candidates[i].edge), candidates[i]};
  std::sort(sorted.begin(), sorted.end(), [](const auto& x, const auto& y) {
    return x.first != y.first ? x.first < y.first : x.second.edge < y.second.edge;
  });
  // A voxel with one candidate changes nothing (a lone fan's vertex goes to its vertices'
  // centroid, here the vertex itself): only voxels with two or more take part.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const bool alone = (i == 0 || sorted[i - 1].first != sorted[i].first) &&
                       (i + 1 == sorted.size() || sorted[i + 1].first != sorted[i].first);
    if (!alone) sorted[kept++] = sorted[i];
  }
  sorted.resize(kept);
  candidates.resize(kept);
  if (sorted.empty()) return report;
  for (std::size_t i = 0; i < sorted.size(); ++i) candidates[i] = sorted[i].second;
  Snapper s(mesh, candidates, frame, min_area);
  std::vector<std::uint32_t> groups;  // each voxel's first candidate, and the end
  for (std::uint32_t b = 0; b < sorted.size(); ++b)
    if (b == 0 || sorted[b].first != sorted[b - 1].first) groups.push_back(b);
  groups.push_back(static_cast<std::uint32_t>(sorted.size()));
  // Voxels by parity class (x, y, z mod 2): two voxels of one class lie two or more apart along
  // some axis, so their stars (the 8 cells around each) share no triangle and no vertex that
  // either moves: a class runs in parallel, and the result does not depend on the order within
  // it. A voxel refused because of a neighbour's vertices not yet merged (a triangle to two
  // vertices that later merge looks degenerate) is tried again once the others are done.
  std::array<std::vector<std::uint32_t>, 8> todo;
  for (std::uint32_t g = 0; g + 1 < groups.size(); ++g) todo[parity(sorted[groups[g]].first)].push_back(g);
  tbb::enumerable_thread_specific<Worker> workers;
  for (int round = 0; round < kSnapRounds; ++round) {
    bool progress = false, left = false;
    for (auto& cls : todo) {
      std::vector<char> refused(cls.size(), 0);
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cls.size(), 64), [&](const auto& r) {
        Worker& w = workers.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const std::uint32_t g = cls[i];
          refused[i] = !s.snap_group(groups[g], groups[g + 1], sorted[groups[g]].first, w);
        }
      });
      std::size_t n = 0;
      for (std::size_t i = 0; i < cls.size(); ++i)
        if (refused[i]) cls[n++] = cls[i];
      progress = progress || n < cls.size();
      cls.resize(n);
      left = left || n > 0;
    }
    if (!progress || !left) break;
  }
  for (const Worker& w : workers) {
    report.moved += w.report.moved;
    report.merged += w.report.merged;
    report.dropped += w.report.dropped;
    report.split += w.report.split;
  }
  // The voxels still refused: their vertices move out along their edges instead (a voxel's star
  // touches no other voxel's of its class; classes in order, so the result is deterministic).
  for (const auto& cls : todo)
    for (std::uint32_t g : cls) {
      report.kept += groups[g + 1] - groups[g];
      if (push > 0) report.pushed += s.push_group(groups[g], groups[g + 1], sorted[groups[g]].first, push);
    }
  s.compact(report);
  return report;

}

}  // namespace isocurv::mc
