#include "mc/bricks.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/floor_div8.h"
#include "core/huge_pages.h"

// GCC's function multiversioning (x86-64 glibc, which resolves it with an ifunc): an AVX2 build
// of a hot loop beside the baseline one.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
#define ISOCURV_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ISOCURV_VECTOR_CLONES
#endif

namespace isocurv::mc {
namespace {

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

namespace {

constexpr int kKeyBits = 21;  // block coordinates (from BrickIndex::first_) a key holds per axis

std::uint64_t block_key(int bx, int by, int bz) {
  return (std::uint64_t(bx) << (2 * kKeyBits)) | (std::uint64_t(by) << kKeyBits) | std::uint64_t(bz);
}
openvdb::Coord times8(const openvdb::Coord& c) { return openvdb::Coord(c.x() * 8, c.y() * 8, c.z() * 8); }

openvdb::Coord key_block(std::uint64_t k) {
  constexpr std::uint64_t kMask = (std::uint64_t(1) << kKeyBits) - 1;
  return openvdb::Coord(int(k >> (2 * kKeyBits)), int((k >> kKeyBits) & kMask), int(k & kMask));
}

std::uint32_t float_bits(float x) {
  std::uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// Sides (voxels) of the regions an OpenVDB float tree stores one value for, by level (3 minus
// the depth Accessor::getValueDepth returns, which is -1 for the background): 0 a leaf voxel
// (its leaf: 8^3 values), 1 a tile of a lower internal node (8^3), 2 a tile of an upper
// internal node (128^3), 3 a root tile or the background (4096^3, aligned).
constexpr int kRegionSide[4] = {8, 8, 128, 4096};

// Finds the faces of constant regions (tiles) where the value beyond differs, for the sparse
// layout: each such face's blocks, on both sides, are marked (keys), so that the bricks reading
// both are indexed. A face beyond the index's upper end is marked on the tile's side (those
// bricks read the background there, as in the dense layout).
class TileFaces {
 public:
  TileFaces(const openvdb::FloatGrid& g, const openvdb::Coord& first, const openvdb::Coord& nblocks,
            std::vector<std::uint64_t>& marks)
      : acc_(g.getConstAccessor()), first_(first), n_(nblocks), marks_(marks) {}

  /// The tile of side `side` (voxels, a multiple of 8) at `origin` holding `value`.
  void tile(const openvdb::Coord& origin, int side, float value) {
    // Block coordinates from first_ (a multiple of 8, as tile origins are): within int.
    const openvdb::Coord lo(origin.x() / 8 - first_.x() / 8, origin.y() / 8 - first_.y() / 8,
                            origin.z() / 8 - first_.z() / 8);
    const openvdb::Coord hi = lo + openvdb::Coord(side / 8 - 1);
    for (int a = 0; a < 3; ++a)  // wholly outside the index: nothing to mark
      if (hi[a] < 0 || lo[a] >= n_[a]) return;
    const std::uint32_t bits = float_bits(value);
    for (int axis = 0; axis < 3; ++axis)
      for (int dir : {-1, 1}) {
        // Blocks along the face: the tile's outer layer (inner), and the layer beyond. A tile that
        // reaches past the index's upper end is cut there: the bricks of its last layer read
        // past the index.
        const int inner = dir < 0 ? lo[axis] : std::min(hi[axis], n_[axis] - 1);
        const int outer = inner + dir;
        if (inner < 0 || outer < 0) continue;  // below the index: no brick reads across it
        openvdb::Coord square = lo;
        square[axis] = outer;
        face(axis, square, side / 8, bits, inner, outer >= n_[axis]);
      }
  }

 private:
  // The square of side `s` blocks at `sq` (block coordinates, in the layer beyond the tile along
  // `axis`) against the tile's value; `past_end`: the layer lies past the index's upper end.
  void face(int axis, const openvdb::Coord& sq, int s, std::uint32_t bits, int inner, bool past_end) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    if (sq[b] >= n_[b] || sq[c] >= n_[c] || sq[b] + s <= 0 || sq[c] + s <= 0) return;
    if (!past_end) {
      const openvdb::Coord voxel = first_ + times8(sq);
      const int level = std::min(3, 3 - acc_.getValueDepth(voxel));
      if (level == 0) {
        if (s == 1) return;  // a leaf: the blocks around every leaf are indexed anyway
      } else if (kRegionSide[level] >= 8 * s) {  // one value over the whole square
        if (float_bits(acc_.getValue(voxel)) == bits) return;
        mark(axis, sq, s, inner, true);
        return;
      }
      const int sub = s > 16 ? 16 : 1;  // the next region size down (128 or 8 voxels)
      for (int i = 0; i < s; i += sub)
        for (int j = 0; j < s; j += sub) {
          openvdb::Coord q = sq;
          q[b] += i;
          q[c] += j;
          face(axis, q, sub, bits, inner, false);
        }
      return;
    }
    mark(axis, sq, s, inner, false);
  }

  void mark(int axis, const openvdb::Coord& sq, int s, int inner, bool beyond) {
    const int b = (axis + 1) % 3, c = (axis + 2) % 3;
    for (int i = std::max(0, sq[b]); i < std::min(n_[b], sq[b] + s); ++i)
      for (int j = std::max(0, sq[c]); j < std::min(n_[c], sq[c] + s); ++j) {
        openvdb::Coord p = sq;
        p[b] = i;
        p[c] = j;
        if (beyond) marks_.push_back(block_key(p.x(), p.y(), p.z()));
        p[axis] = inner;
        marks_.push_back(block_key(p.x(), p.y(), p.z()));
      }
  }

  openvdb::FloatGrid::ConstAccessor acc_;
  openvdb::Coord first_, n_;
  std::vector<std::uint64_t>& marks_;
};

}  // namespace

BrickIndex::BrickIndex(const volume::Volume& v, Layout layout) {
  // Blocks covering every cell any frame may visit (cap adds one layer) plus their apron; of a
  // volume read in part (a rank's slab), only those of the part, so that each rank's index
  // follows its share of the volume, not the whole box.
  openvdb::CoordBBox box = v.domain;
  if (v.slab) box.intersect(*v.slab);
  if (box.empty()) return;
  box.expand(2);
  first_ = openvdb::Coord(floor_div8(box.min().x()) * 8, floor_div8(box.min().y()) * 8,
                          floor_div8(box.min().z()) * 8);
  nx_ = floor_div8(box.max().x()) - first_.x() / 8 + 1;
  ny_ = floor_div8(box.max().y()) - first_.y() / 8 + 1;
  nz_ = floor_div8(box.max().z()) - first_.z() / 8 + 1;
  background_ = v.grid->background();
  if (layout == Layout::automatic) {
    // Dense while the box holds few blocks more than the leaves (its memory then follows them
    // too, and a block is found by arithmetic instead of a lookup).
    const double box_blocks = double(nx_) * ny_ * nz_;
    const double leaves = double(v.grid->tree().leafCount());
    layout = v.dense || box_blocks <= 32 * leaves + 32768 ? Layout::dense : Layout::sparse;
  }
  if (layout == Layout::dense)
    build_dense(v);
  else
    build_sparse(v);
}

void BrickIndex::build_dense(const volume::Volume& v) {
  resize_in_huge_pages(blocks_, std::size_t(nx_) * ny_ * nz_);  // first touches of small pages are slow on VMs
  const openvdb::CoordBBox domain = v.domain;
  const bool dense = v.dense;
  // x fastest: dense volumes' leaves lie in memory in that order, so the scan streams.
  tbb::parallel_for(tbb::blocked_range<int>(0, nz_ * ny_), [&](const tbb::blocked_range<int>& r) {
    auto acc = v.grid->getConstAccessor();
    for (int zy = r.begin(); zy != r.end(); ++zy) {
      const int bz = zy / ny_, by = zy % ny_;
      for (int bx = 0; bx < nx_; ++bx) {
        const openvdb::Coord o = first_ + openvdb::Coord(bx * 8, by * 8, bz * 8);
        blocks_[block_at(bx, by, bz)] = make_block(acc, o, dense, domain);
      }
    }
  });
}

// The sparse layout: the blocks of the leaves and of the marked tile faces (TileFaces) are the
// seeds; the bricks that may straddle are those reading a seed (a seed and the 7 blocks below
// it), and the blocks indexed those the bricks read (a seed and its 26 neighbours).
void BrickIndex::build_sparse(const volume::Volume& v) {
  if (nx_ >= (1 << kKeyBits) || ny_ >= (1 << kKeyBits) || nz_ >= (1 << kKeyBits))
    throw Error(v.path, "volume spans more than 2^24 voxels along an axis; cannot mesh it");
  sparse_ = true;
  const openvdb::FloatTree& tree = v.grid->tree();
  const openvdb::Coord n(nx_, ny_, nz_);
  auto inside = [&](const openvdb::Coord& b) {
    return b.x() >= 0 && b.y() >= 0 && b.z() >= 0 && b.x() < nx_ && b.y() < ny_ && b.z() < nz_;
  };
  std::vector<std::uint64_t> seeds;
  seeds.reserve(tree.leafCount());
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) {
    const openvdb::Coord o = leaf->origin();  // multiples of 8, as first_
    const openvdb::Coord b(o.x() / 8 - first_.x() / 8, o.y() / 8 - first_.y() / 8, o.z() / 8 - first_.z() / 8);
    if (inside(b)) seeds.push_back(block_key(b.x(), b.y(), b.z()));
  }
  // Tiles unlike the background, at every level (the background's own faces, and those between
  // equal values, hold no surface; a face between two tiles is found from either side).
  {
    using Root = openvdb::FloatTree::RootNodeType;
    using Upper = Root::ChildNodeType;
    using Lower = Upper::ChildNodeType;
    TileFaces faces(*v.grid, first_, n, seeds);
    const std::uint32_t background = float_bits(background_);
    auto tile = [&](const openvdb::Coord& origin, int side, float value) {
      if (float_bits(value) != background) faces.tile(origin, side, value);
    };
    const Root& root = tree.root();
    for (auto t = root.cbeginValueAll(); t; ++t) tile(t.getCoord(), Upper::DIM, *t);
    for (auto upper = root.cbeginChildOn(); upper; ++upper) {
      for (auto t = upper->cbeginValueAll(); t; ++t) tile(t.getCoord(), Lower::DIM, *t);
      for (auto lower = upper->cbeginChildOn(); lower; ++lower)
        for (auto t = lower->cbeginValueAll(); t; ++t) tile(t.getCoord(), 8, *t);
    }
  }
  tbb::parallel_sort(seeds.begin(), seeds.end());
  seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
  // Bricks: each seed and the 7 blocks below it; blocks: each seed and its 26 neighbours.
  std::vector<std::uint64_t> bricks, blocks;
  bricks.reserve(seeds.size() * 8);
  blocks.reserve(seeds.size() * 27);
  for (const std::uint64_t k : seeds) {
    const openvdb::Coord s = key_block(k);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const openvdb::Coord b = s + openvdb::Coord(dx, dy, dz);
          if (!inside(b)) continue;
          const std::uint64_t key = block_key(b.x(), b.y(), b.z());
          blocks.push_back(key);
          if (dx <= 0 && dy <= 0 && dz <= 0) bricks.push_back(key);
        }
  }
  // Keys order blocks x, y, z (z fastest): the candidates' order.
  tbb::parallel_sort(bricks.begin(), bricks.end());
  bricks.erase(std::unique(bricks.begin(), bricks.end()), bricks.end());
  tbb::parallel_sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  bricks_.resize(bricks.size());
  for (std::size_t i = 0; i < bricks.size(); ++i) bricks_[i] = key_block(bricks[i]);
  blocks_.resize(blocks.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
    auto acc = v.grid->getConstAccessor();
    for (std::size_t i = r.begin(); i != r.end(); ++i)
      blocks_[i] = make_block(acc, first_ + times8(key_block(blocks[i])), v.dense, v.domain);
  });
  slot_.reserve(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) slot_.emplace(blocks[i], std::uint32_t(i));
}

// One block's ranges, from its leaf or its constant value (a tile or the background).
BrickIndex::Block BrickIndex::make_block(const openvdb::FloatGrid::ConstAccessor& acc, const openvdb::Coord& o,
                                         bool dense, const openvdb::CoordBBox& domain) {
  BrickIndex::Block b;
  if (const auto* leaf = acc.probeConstLeaf(o)) {
    b = leaf_block(leaf->buffer().data());
  } else {
    const float x = acc.getValue(o);  // a tile or background: constant over the block
    b = BrickIndex::Block{};
    b.tile = x;
    const bool finite = std::isfinite(x);
    const BrickIndex::Range r{finite ? x : std::numeric_limits<float>::max(),
                              finite ? x : std::numeric_limits<float>::lowest()};
    for (BrickIndex::Range& p : b.part) p = r;
    b.nonfinite = !finite;
  }
  b.clipped = dense && !domain.isInside(openvdb::CoordBBox(o, o + openvdb::Coord(7)));
  return b;
}

// Whether a brick whose eight blocks (own first, then d = dx + 2 dy + 4 dz above; null past the
// index) are `blk` may straddle `iso`: judged by the ranges of just the samples it reads.
bool BrickIndex::may_straddle(const Block* const* blk, bool above, float iso) {
  bool in = false, out_side = false;
  for (int d = 0; d < 8; ++d) {
    const BrickIndex::Block* b = blk[d];
    if (!b) {
      out_side = true;
      continue;
    }
    if (b->nonfinite || b->clipped) out_side = true;
    const BrickIndex::Range& r = b->part[d];
    if (r.min > r.max) continue;
    if (above ? r.max > iso : r.min < iso) in = true;
    if (above ? r.min <= iso : r.max >= iso) out_side = true;
    if (in && out_side) return true;  // often at d = 0: the brick's own block straddles
  }
  return in && out_side;
}

const BrickIndex::Block* BrickIndex::find(int bx, int by, int bz) const {
  if (bx < 0 || by < 0 || bz < 0 || bx >= nx_ || by >= ny_ || bz >= nz_) return nullptr;
  if (!sparse_) return &blocks_[block_at(bx, by, bz)];
  const auto it = slot_.find(block_key(bx, by, bz));
  return it == slot_.end() ? nullptr : &blocks_[it->second];
}

std::vector<openvdb::Coord> BrickIndex::candidates(const Frame& f) const {
  std::vector<openvdb::Coord> out;
  if (f.cells.empty() || blocks_.empty()) return out;
  // The frame's bricks, within the index (a volume read in part indexes only its part).
  const int bx0 = std::max(floor_div8(f.cells.min().x()) - first_.x() / 8, 0);
  const int by0 = std::max(floor_div8(f.cells.min().y()) - first_.y() / 8, 0);
  const int bz0 = std::max(floor_div8(f.cells.min().z()) - first_.z() / 8, 0);
  const int bx1 = std::min(floor_div8(f.cells.max().x()) - first_.x() / 8, nx_ - 1);
  const int by1 = std::min(floor_div8(f.cells.max().y()) - first_.y() / 8, ny_ - 1);
  const int bz1 = std::min(floor_div8(f.cells.max().z()) - first_.z() / 8, nz_ - 1);
  const bool above = f.sign > 0;
  const float iso = f.isovalue;
  // The brick's samples lie in its own block and in a lower face, line or corner of each block
  // one step up along some axes (Block::part).
  auto sparse_test = [&](int bx, int by, int bz) {
    const Block* blk[8];
    for (int d = 0; d < 8; ++d) blk[d] = find(bx + (d & 1), by + ((d >> 1) & 1), bz + (d >> 2));
    return may_straddle(blk, above, iso);
  };
  auto dense_test = [&](int bx, int by, int bz) {  // bx, by, bz >= 0: the range lies in the index
    const Block* blk[8];
    for (int d = 0; d < 8; ++d) {
      const int x = bx + (d & 1), y = by + ((d >> 1) & 1), z = bz + (d >> 2);
      blk[d] = x < nx_ && y < ny_ && z < nz_ ? &blocks_[block_at(x, y, z)] : nullptr;
    }
    return may_straddle(blk, above, iso);
  };
  std::vector<std::vector<openvdb::Coord>> parts;
  if (sparse_) {
    // The bricks that may straddle at some isovalue, in order; chunks in parallel, joined in order.
    constexpr std::size_t kChunk = 4096;
    parts.resize((bricks_.size() + kChunk - 1) / kChunk);
    tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t c) {
      for (std::size_t i = c * kChunk; i < std::min(bricks_.size(), (c + 1) * kChunk); ++i) {
        const openvdb::Coord& b = bricks_[i];
        if (b.x() < bx0 || b.x() > bx1 || b.y() < by0 || b.y() > by1 || b.z() < bz0 || b.z() > bz1) continue;
        if (sparse_test(b.x(), b.y(), b.z())) parts[c].push_back(first_ + times8(b));
      }
    });
  } else {
    // z innermost, as in VDB leaves: a brick's apron along z is the next brick's own leaf, still
    // in cache when that brick is gathered. Slices of constant x in parallel, joined in order.
    parts.resize(std::size_t(std::max(0, bx1 - bx0 + 1)));
    tbb::parallel_for(tbb::blocked_range<int>(bx0, bx1 + 1), [&](const tbb::blocked_range<int>& range) {
      for (int bx = range.begin(); bx != range.end(); ++bx) {
        std::vector<openvdb::Coord>& slice = parts[std::size_t(bx - bx0)];
        for (int by = by0; by <= by1; ++by)
          for (int bz = bz0; bz <= bz1; ++bz)
            if (dense_test(bx, by, bz)) slice.push_back(first_ + openvdb::Coord(bx * 8, by * 8, bz * 8));
      }
    });
  }
  std::size_t total = 0;
  for (const auto& part : parts) total += part.size();
  out.reserve(total);
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
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
        const Block* blk = sparse_                            ? find(x, y, z)
                           : x < nx_ && y < ny_ && z < nz_ ? &blocks_[block_at(x, y, z)]
                                                              : nullptr;
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
