#include "mc/bricks.h"

#include "core/huge_pages.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

// GCC's function multiversioning (x86-64 glibc, which resolves it with an ifunc): an AVX2 build
// of a hot loop beside the baseline one.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
#define ISOCURV_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ISOCURV_VECTOR_CLONES
#endif

namespace isocurv::mc {
namespace {

int floor_div8(int v) { return v >= 0 ? v / 8 : -((-v + 7) / 8); }

// 8-lane vectors (GCC/Clang vector extensions): AVX2 registers in the AVX2 builds.
typedef float Float8 __attribute__((vector_size(32)));
typedef std::int32_t Int8 __attribute__((vector_size(32)));

// A brick's gather from its eight blocks' values (leaf buffers, or leaf-sized buffers of a tile's
// value), before any clipping to the domain. Column (x, y): z = 0..7 straight from one block
// (VDB's order is z fastest too), z = 8 from the block after it along z. Writes the 729 signed
// values to `out`; true when some are inside and some are not. A column's first 8 values are
// converted as one 8-lane vector, branch-free.
ISOCURV_VECTOR_CLONES bool gather_leaves(const float* const* data, float sign, float iso, float outside_value,
                                         float* out) {
  constexpr std::int32_t kAbs = 0x7fffffff, kInf = 0x7f800000;  // |bits| < kInf: finite
  const Float8 zero = {}, sign8 = zero + sign, iso8 = zero + iso;
  const Int8 outside8 = (Int8)(zero + outside_value);
  Int8 in8 = {}, out8 = {};
  bool any_in = false, any_out = false;
  for (int x = 0; x < kApron; ++x)
    for (int y = 0; y < kApron; ++y) {
      const int k = (x >> 3) | ((y >> 3) << 1);
      const int offset = ((x & 7) << 6) | ((y & 7) << 3);
      Float8 v;
      std::memcpy(&v, data[k] + offset, sizeof v);
      const Int8 finite = ((Int8)v & kAbs) < kInf;  // lanes all ones where finite
      const Float8 sv = (Float8)(((Int8)(sign8 * (v - iso8)) & finite) | (outside8 & ~finite));
      std::memcpy(out, &sv, sizeof sv);
      const Int8 inside = sv > zero;
      in8 |= inside;
      out8 |= ~inside;
      const float last = data[k | 4][offset];  // z = 8
      const float s = std::fabs(last) <= std::numeric_limits<float>::max() ? sign * (last - iso) : outside_value;
      out[kBrick] = s;
      any_in |= s > 0;
      any_out |= !(s > 0);
      out += kApron;
    }
  for (int j = 0; j < 8; ++j) {
    any_in |= in8[j] != 0;
    any_out |= out8[j] != 0;
  }
  return any_in && any_out;
}

// Samples of the brick at `o` that lie outside the data domain of a clipped (dense) volume read
// as outside (Frame::signed_value). True when the brick still straddles.
bool clip_to_domain(const Frame& f, const openvdb::Coord& o, float* out) {
  bool in = false, outside = false;
  for (int x = 0; x < kApron; ++x)
    for (int y = 0; y < kApron; ++y)
      for (int z = 0; z < kApron; ++z, ++out) {
        if (!f.domain.isInside(o + openvdb::Coord(x, y, z))) *out = f.clipped;
        in |= *out > 0;
        outside |= !(*out > 0);
      }
  return in && outside;
}

}  // namespace

// The finite value ranges of a leaf's 512 values (VDB order: 64 x + 8 y + z) and of the parts of
// it a lower neighbour's apron reads (Block::part), and whether any value is NaN or infinite.
// The common case, every value finite, takes plain minima and maxima 16 values a step (8-lane
// vectors; a NaN never wins a comparison and is counted apart), built twice, for AVX2 and for any
// x86-64, the loader picking one for the CPU at hand; a leaf holding a NaN, or whose range
// reaches an infinity, is redone by leaf_block_nonfinite.
ISOCURV_VECTOR_CLONES BrickIndex::Block BrickIndex::leaf_block(const float* d) {
  constexpr float kMax = std::numeric_limits<float>::max(), kLowest = std::numeric_limits<float>::lowest();
  const Float8 zero = {}, inf = zero + std::numeric_limits<float>::infinity();
  // 16 values a step, y = 2 c (lanes of a) and 2 c + 1 (lanes of b); y = 0 is the a of c = 0.
  Float8 lo = inf, hi = -inf, lo_b = inf, hi_b = -inf, ylo = inf, yhi = -inf;
  Int8 nan = {};
  float zlo = std::numeric_limits<float>::infinity(), zhi = -zlo;  // z = 0: lane 0 of a and of b
  // Vectors pass by reference: by value they would cross from the AVX2 build into a lambda built
  // for the baseline ABI wherever the compiler does not inline it (-O2), and arrive garbled.
  auto range = [](const Float8& l, const Float8& h) {
    Range r{l[0], h[0]};
    for (int j = 1; j < 8; ++j) {
      r.min = l[j] < r.min ? l[j] : r.min;
      r.max = h[j] > r.max ? h[j] : r.max;
    }
    return r;
  };
  Block b{};
  for (int x = 0; x < 8; ++x) {
    for (int c = 0; c < 4; ++c) {
      Float8 va, vb;
      std::memcpy(&va, d + 64 * x + 16 * c, sizeof va);
      std::memcpy(&vb, d + 64 * x + 16 * c + 8, sizeof vb);
      lo = va < lo ? va : lo;
      hi = va > hi ? va : hi;
      lo_b = vb < lo_b ? vb : lo_b;
      hi_b = vb > hi_b ? vb : hi_b;
      nan |= (va != va) | (vb != vb);
      if (c == 0) {
        ylo = va < ylo ? va : ylo;
        yhi = va > yhi ? va : yhi;
      }
      zlo = std::min({zlo, va[0], vb[0]});
      zhi = std::max({zhi, va[0], vb[0]});
    }
    if (x == 0) b.part[1] = range(lo < lo_b ? lo : lo_b, hi > hi_b ? hi : hi_b);
  }
  b.part[0] = range(lo < lo_b ? lo : lo_b, hi > hi_b ? hi : hi_b);
  bool any_nan = false;
  for (int j = 0; j < 8; ++j) any_nan |= nan[j] != 0;
  if (any_nan || !(b.part[0].min >= kLowest && b.part[0].max <= kMax)) return leaf_block_nonfinite(d);
  b.part[2] = range(ylo, yhi);
  b.part[4] = Range{zlo, zhi};
  auto line = [&](int step) {  // the 8 values from the corner along one axis
    Range r{d[0], d[0]};
    for (int i = 1; i < 8; ++i) {
      r.min = std::min(r.min, d[i * step]);
      r.max = std::max(r.max, d[i * step]);
    }
    return r;
  };
  b.part[3] = line(1);   // x = y = 0, along z
  b.part[5] = line(8);   // x = z = 0, along y
  b.part[6] = line(64);  // y = z = 0, along x
  b.part[7] = Range{d[0], d[0]};
  b.leaf = d;
  return b;
}

// leaf_block for a leaf that holds NaN or infinite values: the ranges of its finite values (a NaN
// never wins a comparison, so it falls out of the ranges by itself; infinities are masked to the
// start values), flagged nonfinite.
BrickIndex::Block BrickIndex::leaf_block_nonfinite(const float* d) {
  constexpr int kLanes = 16;
  constexpr float kMax = std::numeric_limits<float>::max(), kLowest = std::numeric_limits<float>::lowest();
  float lo[kLanes], hi[kLanes], ylo[8], yhi[8], zlo = kMax, zhi = kLowest;
  int bad[kLanes];
  for (int j = 0; j < kLanes; ++j) {
    lo[j] = kMax;
    hi[j] = kLowest;
    bad[j] = 0;
  }
  for (int j = 0; j < 8; ++j) {
    ylo[j] = kMax;
    yhi[j] = kLowest;
  }
  auto reduce = [&](const float* l, const float* h, int n) {
    Range r{l[0], h[0]};
    for (int j = 1; j < n; ++j) {
      r.min = std::min(r.min, l[j]);
      r.max = std::max(r.max, h[j]);
    }
    return r;
  };
  Block b{};
  for (int x = 0; x < 8; ++x) {
    for (int c = 0; c < 4; ++c) {  // 16 values: y = 2 c (lanes 0-7) and 2 c + 1 (lanes 8-15)
      const float* v = d + 64 * x + 16 * c;
      float in_lo[kLanes], in_hi[kLanes];
      for (int j = 0; j < kLanes; ++j) {
        const bool finite = std::fabs(v[j]) <= kMax;  // false for NaN and infinities
        bad[j] |= !finite;
        in_lo[j] = finite ? v[j] : kMax;
        in_hi[j] = finite ? v[j] : kLowest;
        lo[j] = in_lo[j] < lo[j] ? in_lo[j] : lo[j];
        hi[j] = in_hi[j] > hi[j] ? in_hi[j] : hi[j];
      }
      if (c == 0)  // y = 0
        for (int j = 0; j < 8; ++j) {
          ylo[j] = in_lo[j] < ylo[j] ? in_lo[j] : ylo[j];
          yhi[j] = in_hi[j] > yhi[j] ? in_hi[j] : yhi[j];
        }
      zlo = std::min({zlo, in_lo[0], in_lo[8]});  // z = 0
      zhi = std::max({zhi, in_hi[0], in_hi[8]});
    }
    if (x == 0) b.part[1] = reduce(lo, hi, kLanes);
  }
  b.part[0] = reduce(lo, hi, kLanes);
  b.part[2] = reduce(ylo, yhi, 8);
  b.part[4] = Range{zlo, zhi};
  auto line = [&](int step) {  // the 8 values from the corner along one axis
    Range r{kMax, kLowest};
    for (int i = 0; i < 8; ++i) {
      const float x = d[i * step];
      if (!(std::fabs(x) <= kMax)) continue;  // NaN or infinite
      r.min = std::min(r.min, x);
      r.max = std::max(r.max, x);
    }
    return r;
  };
  b.part[3] = line(1);   // x = y = 0, along z
  b.part[5] = line(8);   // x = z = 0, along y
  b.part[6] = line(64);  // y = z = 0, along x
  const bool corner_finite = std::fabs(d[0]) <= kMax;
  b.part[7] = corner_finite ? Range{d[0], d[0]} : Range{kMax, kLowest};
  for (int j = 0; j < kLanes; ++j) b.nonfinite |= bad[j] != 0;
  b.leaf = d;
  return b;
}

BrickIndex::BrickIndex(const volume::Volume& v) {
  // Blocks covering every cell any frame may visit (cap adds one layer) plus their apron.
  openvdb::CoordBBox box = v.domain;
  if (box.empty()) return;
  box.expand(2);
  first_ = openvdb::Coord(floor_div8(box.min().x()) * 8, floor_div8(box.min().y()) * 8,
                          floor_div8(box.min().z()) * 8);
  nx_ = floor_div8(box.max().x()) - first_.x() / 8 + 1;
  ny_ = floor_div8(box.max().y()) - first_.y() / 8 + 1;
  nz_ = floor_div8(box.max().z()) - first_.z() / 8 + 1;
  resize_in_huge_pages(blocks_, std::size_t(nx_) * ny_ * nz_);  // first touches of small pages are slow on VMs
  background_ = v.grid->background();
  const openvdb::CoordBBox domain = v.domain;
  const bool dense = v.dense;
  // x fastest: dense volumes' leaves lie in memory in that order, so the scan streams.
  tbb::parallel_for(tbb::blocked_range<int>(0, nz_ * ny_), [&](const tbb::blocked_range<int>& r) {
    auto acc = v.grid->getConstAccessor();
    for (int zy = r.begin(); zy != r.end(); ++zy) {
      const int bz = zy / ny_, by = zy % ny_;
      for (int bx = 0; bx < nx_; ++bx) {
        const openvdb::Coord o = first_ + openvdb::Coord(bx * 8, by * 8, bz * 8);
        Block b;
        if (const auto* leaf = acc.probeConstLeaf(o)) {
          b = leaf_block(leaf->buffer().data());
        } else {
          const float x = acc.getValue(o);  // a tile or background: constant over the block
          b = Block{};
          b.tile = x;
          const bool finite = std::isfinite(x);
          const Range r{finite ? x : std::numeric_limits<float>::max(),
                        finite ? x : std::numeric_limits<float>::lowest()};
          for (Range& p : b.part) p = r;
          b.nonfinite = !finite;
        }
        b.clipped = dense && !domain.isInside(openvdb::CoordBBox(o, o + openvdb::Coord(7)));
        blocks_[block_at(bx, by, bz)] = b;
      }
    }
  });
}

std::vector<openvdb::Coord> BrickIndex::candidates(const Frame& f) const {
  std::vector<openvdb::Coord> out;
  if (f.cells.empty() || blocks_.empty()) return out;
  const int bx0 = floor_div8(f.cells.min().x()) - first_.x() / 8;
  const int by0 = floor_div8(f.cells.min().y()) - first_.y() / 8;
  const int bz0 = floor_div8(f.cells.min().z()) - first_.z() / 8;
  const int bx1 = floor_div8(f.cells.max().x()) - first_.x() / 8;
  const int by1 = floor_div8(f.cells.max().y()) - first_.y() / 8;
  const int bz1 = floor_div8(f.cells.max().z()) - first_.z() / 8;
  const bool above = f.sign > 0;
  const float iso = f.isovalue;
  // z innermost, as in VDB leaves: a brick's apron along z is the next brick's own leaf, still in
  // cache when that brick is gathered. Slices of constant x in parallel, joined in order.
  std::vector<std::vector<openvdb::Coord>> slices(std::size_t(std::max(0, bx1 - bx0 + 1)));
  tbb::parallel_for(tbb::blocked_range<int>(bx0, bx1 + 1), [&](const tbb::blocked_range<int>& range) {
    for (int bx = range.begin(); bx != range.end(); ++bx) {
      std::vector<openvdb::Coord>& slice = slices[std::size_t(bx - bx0)];
      for (int by = by0; by <= by1; ++by)
        for (int bz = bz0; bz <= bz1; ++bz) {
          bool in = false, out_side = false;
          // The brick's samples lie in its own block and in a lower face, line or corner of each
          // block one step up along some axes (Block::part).
          for (int d = 0; d < 8; ++d) {
            const int x = bx + (d & 1), y = by + ((d >> 1) & 1), z = bz + (d >> 2);
            if (x >= nx_ || y >= ny_ || z >= nz_) { out_side = true; continue; }
            const Block& b = blocks_[block_at(x, y, z)];
            if (b.nonfinite || b.clipped) out_side = true;
            const Range& r = b.part[d];
            if (r.min > r.max) continue;
            if (above ? r.max > iso : r.min < iso) in = true;
            if (above ? r.min <= iso : r.max >= iso) out_side = true;
            if (in && out_side) break;  // often at d = 0: the brick's own block straddles
          }
          if (in && out_side) slice.push_back(first_ + openvdb::Coord(bx * 8, by * 8, bz * 8));
        }
    }
  });
  std::size_t total = 0;
  for (const auto& slice : slices) total += slice.size();
  out.reserve(total);
  for (const auto& slice : slices) out.insert(out.end(), slice.begin(), slice.end());
  return out;
}

void BrickIndex::gather(const Frame& f, std::vector<openvdb::Coord>& origins, float* samples) const {
  const std::size_t n = origins.size();
  std::vector<char> keep(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 16), [&](const tbb::blocked_range<std::size_t>& r) {
    // A block without a leaf (a tile, or past the index: the background) reads as a leaf-sized
    // buffer of its constant value, filled when the value changes.
    float tiles[8][512];
    std::uint32_t tile_bits[8];
    bool tile_filled[8] = {};
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      const openvdb::Coord o = origins[b];
      // The brick's samples come from its own 8^3 block and the seven blocks above it (VDB leaf
      // offset = 64 x + 8 y + z).
      const float* data[8];
      const int bx = (o.x() - first_.x()) / 8, by = (o.y() - first_.y()) / 8, bz = (o.z() - first_.z()) / 8;
      for (int k = 0; k < 8; ++k) {
        const int x = bx + (k & 1), y = by + ((k >> 1) & 1), z = bz + (k >> 2);
        const Block* blk = x < nx_ && y < ny_ && z < nz_ ? &blocks_[block_at(x, y, z)] : nullptr;
        data[k] = blk ? blk->leaf : nullptr;
        if (data[k]) continue;
        const float value = blk ? blk->tile : background_;
        std::uint32_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        if (!tile_filled[k] || tile_bits[k] != bits) {
          std::fill_n(tiles[k], 512, value);
          tile_filled[k] = true;
          tile_bits[k] = bits;
        }
        data[k] = tiles[k];
      }
      float* out = samples + b * kBrickSamples;
      bool straddles = gather_leaves(data, f.sign, f.isovalue, f.outside, out);
      if (f.clip && !f.domain.isInside(openvdb::CoordBBox(o, o + openvdb::Coord(kBrick))))
        straddles = clip_to_domain(f, o, out);
      keep[b] = straddles;
    }
  });
  // Drop the bricks that do not straddle after all (order kept).
  std::size_t w = 0;
  for (std::size_t b = 0; b < n; ++b) {
    if (!keep[b]) continue;
    if (w != b) {
      origins[w] = origins[b];
      std::copy_n(samples + b * kBrickSamples, kBrickSamples, samples + w * kBrickSamples);
    }
    ++w;
  }
  origins.resize(w);
}

}  // namespace isocurv::mc
