#include "volume/dense_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "volume/prefilter.h"

namespace isocurv::volume {
namespace {

std::atomic<std::uint64_t> next_id{1};

/// The sample-index box [box[0], box[1]] x [box[2], box[3]] x [box[4], box[5]] of the bricks for
/// whose number keep() accepts; false when none does.
template <class Keep>
bool brick_index_box(const DenseField& f, const Keep& keep, std::array<int, 6>& box) {
  int lo[3] = {f.bx, f.by, f.bz}, hi[3] = {-1, -1, -1};
  for (int c = 0; c < f.bz; ++c)
    for (int b = 0; b < f.by; ++b)
      for (int a = 0; a < f.bx; ++a) {
        if (!keep(a + std::int64_t(f.bx) * (b + std::int64_t(f.by) * c))) continue;
        const int q[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
      }
  if (hi[0] < 0) return false;
  const int n[3] = {f.nx, f.ny, f.nz};
  for (int k = 0; k < 3; ++k)
    box[2 * k] = lo[k] * kFieldBrick,
            box[2 * k + 1] = std::min(n[k] - 1, (hi[k] + 1) * kFieldBrick);
  return true;
}

}  // namespace

DenseField::DenseField(const Volume& v) : id(next_id++) {
  if (!v.grid) throw Error(v.path, "no volume");
  openvdb::CoordBBox box = v.domain;
  if (!v.dense || box.empty()) box = v.grid->evalActiveVoxelBoundingBox();
  if (box.empty()) throw Error(v.path, "the volume holds no voxels");
  if (!v.grid->transform().isLinear()) throw Error(v.path, "the volume's transform is not affine");
  openvdb::Coord d = box.dim();
  if (d.x() < 2 || d.y() < 2 || d.z() < 2)
    throw Error(v.path, "the volume is thinner than 2 voxels along an axis");
  const std::uint64_t samples = std::uint64_t(d.x()) * d.y() * d.z();
  sparse = samples > kMaxFieldSamples && !v.dense;
  if (samples > kMaxFieldSamples && !sparse)
    throw Error(v.path, "the volume's box holds " + std::to_string(samples) +
                            " voxels, more than the dense field's limit of " +
                            std::to_string(kMaxFieldSamples) + " (2^28)");
  sign = v.inside == Inside::Above ? 1.0f : -1.0f;
  openvdb::Coord lo = box.min();
  const openvdb::FloatGrid& grid = *v.grid;
  if (sparse) {
    // Tiles are the VDB's leaves: the box starts on a leaf's corner.
    for (int c = 0; c < 3; ++c) lo[c] = lo[c] & ~(kFieldTile - 1);
    d = box.max() - lo + openvdb::Coord(1);
    nx = d.x(), ny = d.y(), nz = d.z();
    fill_tiles(grid, lo, v.path);
  } else {
    nx = d.x(), ny = d.y(), nz = d.z();
    values.resize(samples);
    tbb::parallel_for(tbb::blocked_range<int>(0, nz), [&](const tbb::blocked_range<int>& r) {
      auto acc = grid.getConstAccessor();
      for (int k = r.begin(); k != r.end(); ++k)
        for (int j = 0; j < ny; ++j)
          for (int i = 0; i < nx; ++i)
            values[std::size_t(i) + std::size_t(nx) * (j + std::size_t(ny) * k)] =
                acc.getValue(lo + openvdb::Coord(i, j, k));
    });
  }

  bx = (nx - 1 + kFieldBrick - 1) / kFieldBrick;
  by = (ny - 1 + kFieldBrick - 1) / kFieldBrick;
  bz = (nz - 1 + kFieldBrick - 1) / kFieldBrick;
  rank_bricks();

  const openvdb::math::Transform& xf = grid.transform();
  const openvdb::Vec3d o = xf.indexToWorld(lo);
  Eigen::Matrix3d a;
  for (int c = 0; c < 3; ++c) {
    openvdb::Coord e = lo;
    e[c] += 1;
    const openvdb::Vec3d col = xf.indexToWorld(e) - o;
    for (int r = 0; r < 3; ++r) a(r, c) = col[r];
  }
  const Eigen::Matrix3d inv = a.inverse(), it = inv.transpose();
  const Eigen::Vector3d ob(o.x(), o.y(), o.z()), ib = -inv * ob;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      to_world[4 * r + c] = a(r, c);
      to_index[4 * r + c] = inv(r, c);
      normal_matrix[3 * r + c] = it(r, c);
    }
    to_world[4 * r + 3] = ob[r];
    to_index[4 * r + 3] = ib[r];
  }
  bounds = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (int i = 0; i < 8; ++i) {
    const auto w = world({double((i & 1) * (nx - 1)), double(((i >> 1) & 1) * (ny - 1)),
                          double(((i >> 2) & 1) * (nz - 1))});
    for (int c = 0; c < 3; ++c)
      bounds[2 * c] = std::min(bounds[2 * c], w[c]),
                 bounds[2 * c + 1] = std::max(bounds[2 * c + 1], w[c]);
  }
}

std::array<double, 3> DenseField::world(const std::array<double, 3>& q) const {
  std::array<double, 3> w;
  for (int r = 0; r < 3; ++r)
    w[r] = to_world[4 * r] * q[0] + to_world[4 * r + 1] * q[1] + to_world[4 * r + 2] * q[2] +
           to_world[4 * r + 3];
  return w;
}

std::array<float, 36> DenseField::device_transform() const {
  std::array<float, 36> xf{};
  for (int i = 0; i < 12; ++i) xf[i] = float(to_index[i]), xf[12 + i] = float(to_world[i]);
  for (int i = 0; i < 9; ++i) xf[24 + i] = float(normal_matrix[i]);
  return xf;
}

double DenseField::shortest_voxel_edge() const {
  double best = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c)
    best = std::min(best, std::sqrt(to_world[c] * to_world[c] + to_world[4 + c] * to_world[4 + c] +
                                    to_world[8 + c] * to_world[8 + c]));
  return best;
}

void DenseField::fill_tiles(const openvdb::FloatGrid& grid, const openvdb::Coord& lo,
                            const std::string& path) {
  tiles_x = (nx + kFieldTile - 1) / kFieldTile;
  tiles_y = (ny + kFieldTile - 1) / kFieldTile;
  tiles_z = (nz + kFieldTile - 1) / kFieldTile;
  const std::size_t tiles = std::size_t(tiles_x) * tiles_y * tiles_z;
  if (tiles > kMaxFieldTiles)
    throw Error(path, "the volume's box (" + std::to_string(nx) + " x " + std::to_string(ny) +
                          " x " + std::to_string(nz) + " voxels) is too large even for the " +
                          "sparse field's tile table");
  // Which tiles have a leaf, in tile order: their slots.
  std::vector<std::int32_t> slot(tiles, -1);
  std::vector<float> constant(tiles, 0.0f);
  std::int64_t leaves = 0;
  {
    auto acc = grid.getConstAccessor();
    for (int tk = 0; tk < tiles_z; ++tk)
      for (int tj = 0; tj < tiles_y; ++tj)
        for (int ti = 0; ti < tiles_x; ++ti) {
          const std::size_t t = std::size_t(ti) + std::size_t(tiles_x) * (tj + std::size_t(tiles_y) * tk);
          const openvdb::Coord c = lo + openvdb::Coord(ti * kFieldTile, tj * kFieldTile, tk * kFieldTile);
          if (acc.probeConstLeaf(c)) {
            slot[t] = std::int32_t(leaves++);
          } else {
            constant[t] = acc.getValue(c);  // a VDB tile's value or the background: all 8^3
          }
        }
  }
  if (std::uint64_t(leaves) * 512 > kMaxFieldSamples)
    throw Error(path, "the volume's " + std::to_string(leaves) + " leaves hold " +
                          std::to_string(leaves * 512) + " voxels, more than the field's limit of " +
                          std::to_string(kMaxFieldSamples) + " (2^28)");
  values.assign(2 * tiles + std::size_t(leaves) * 512, 0.0f);
  for (std::size_t t = 0; t < tiles; ++t) {
    std::memcpy(&values[t], &slot[t], sizeof(std::int32_t));
    values[tiles + t] = constant[t];
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles), [&](const tbb::blocked_range<std::size_t>& r) {
    auto acc = grid.getConstAccessor();
    for (std::size_t t = r.begin(); t != r.end(); ++t) {
      if (slot[t] < 0) continue;
      const int ti = int(t % tiles_x), tj = int((t / tiles_x) % tiles_y), tk = int(t / (std::size_t(tiles_x) * tiles_y));
      const openvdb::Coord c = lo + openvdb::Coord(ti * kFieldTile, tj * kFieldTile, tk * kFieldTile);
      const auto* leaf = acc.probeConstLeaf(c);
      float* out = &values[2 * tiles + std::size_t(slot[t]) * 512];
      for (int k = 0; k < kFieldTile; ++k)
        for (int j = 0; j < kFieldTile; ++j)
          for (int i = 0; i < kFieldTile; ++i)
            out[i + kFieldTile * (j + kFieldTile * k)] = leaf->getValue(c + openvdb::Coord(i, j, k));
    }
  });
}

bool DenseField::constant_brick(int a, int b, int c, int i1, int j1, int k1,
                                std::array<float, 2>& range, float& slope) const {
  // The tiles brick (a, b, c) reads: its samples 8a .. i1 lie in tiles a and i1 / 8.
  static_assert(kFieldBrick == kFieldTile, "a brick reads at most 2 tiles per axis");
  const std::size_t tiles = std::size_t(tiles_x) * tiles_y * tiles_z;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  bool finite = true;
  for (int tk = c; tk <= k1 / kFieldTile; ++tk)
    for (int tj = b; tj <= j1 / kFieldTile; ++tj)
      for (int ti = a; ti <= i1 / kFieldTile; ++ti) {
        const std::size_t t = std::size_t(ti) + std::size_t(tiles_x) * (tj + std::size_t(tiles_y) * tk);
        std::int32_t slot;
        std::memcpy(&slot, &values[t], sizeof slot);
        if (slot >= 0) return false;  // a stored tile: scan the samples
        const float v = values[tiles + t];
        if (!std::isfinite(v)) {
          finite = false;
          continue;
        }
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
  range = {lo, hi};
  // Neighbouring samples differ by at most hi - lo (a bound, as brick_slope promises).
  slope = finite ? (lo <= hi ? hi - lo : 0.0f) : std::numeric_limits<float>::infinity();
  return true;
}

void DenseField::rank_bricks() {
  brick_range.assign(std::size_t(bx) * by * bz,
                     {std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()});
  brick_slope.assign(brick_range.size(), 0.0f);
  tbb::parallel_for(tbb::blocked_range<int>(0, bz), [&](const tbb::blocked_range<int>& r) {
    for (int c = r.begin(); c != r.end(); ++c)
      for (int b = 0; b < by; ++b)
        for (int a = 0; a < bx; ++a) {
          const std::size_t bi = std::size_t(a) + std::size_t(bx) * (b + std::size_t(by) * c);
          auto& range = brick_range[bi];
          float& slope = brick_slope[bi];
          const int i1 = std::min(nx - 1, (a + 1) * kFieldBrick);
          const int j1 = std::min(ny - 1, (b + 1) * kFieldBrick);
          const int k1 = std::min(nz - 1, (c + 1) * kFieldBrick);
          if (sparse && constant_brick(a, b, c, i1, j1, k1, range, slope)) continue;
          auto at = [&](int i, int j, int k) { return sample(i, j, k); };
          for (int k = c * kFieldBrick; k <= k1; ++k)
            for (int j = b * kFieldBrick; j <= j1; ++j)
              for (int i = a * kFieldBrick; i <= i1; ++i) {
                const float s = at(i, j, k);
                if (!std::isfinite(s)) {
                  slope = std::numeric_limits<float>::infinity();
                  continue;
                }
                range[0] = std::min(range[0], s), range[1] = std::max(range[1], s);
                if (i < i1) slope = std::max(slope, std::abs(at(i + 1, j, k) - s));
                if (j < j1) slope = std::max(slope, std::abs(at(i, j + 1, k) - s));
                if (k < k1) slope = std::max(slope, std::abs(at(i, j, k + 1) - s));
              }
          // A non-finite neighbour makes the difference NaN, which max() skips: the NaN test
          // above sets infinity when that sample itself is visited.
        }
  });
}

void DenseField::smooth(double sigma) {
  if (!(sigma >= 0) || !(sigma <= kMaxSmoothingVoxels))
    throw Error("smoothing must be 0 to " + std::to_string(int(kMaxSmoothingVoxels)) +
                " voxels, not " + std::to_string(sigma));
  if (sigma == 0) return;
  if (sparse)
    throw Error("smoothing needs a dense field: this sparse volume's box holds more than 2^28 "
                "voxels (it is read through its 8^3 leaves); leave the smoothing out");
  const PrefilterTaps taps = prefilter_taps(sigma * sigma);
  std::vector<float> out(values.size());
  const int reach = taps.radius;
  // Along x: each line of samples is contiguous.
  tbb::parallel_for(tbb::blocked_range<int>(0, ny * nz), [&](const tbb::blocked_range<int>& r) {
    for (int row = r.begin(); row != r.end(); ++row) {
      const std::size_t start = std::size_t(nx) * row;
      for (int i = 0; i < nx; ++i) {
        const float here = values[start + i];
        if (!std::isfinite(here)) {
          out[start + i] = here;
          continue;
        }
        double sum = 0, weight = 0;
        for (int t = -reach; t <= reach; ++t) {
          const float v = values[start + std::min(std::max(i + t, 0), nx - 1)];
          if (std::isfinite(v)) sum += taps.w[t + reach] * v, weight += taps.w[t + reach];
        }
        out[start + i] = float(sum / weight);
      }
    }
  });
  values.swap(out);
  // Along y and z: whole rows along x at a time, one tap after the other, so every read streams.
  for (int axis = 1; axis < 3; ++axis) {
    const int n = axis == 1 ? ny : nz;
    const std::ptrdiff_t stride = axis == 1 ? nx : std::ptrdiff_t(nx) * ny;
    tbb::parallel_for(tbb::blocked_range<int>(0, ny * nz), [&](const tbb::blocked_range<int>& r) {
      std::vector<double> sum(nx), weight(nx);
      for (int row = r.begin(); row != r.end(); ++row) {
        const int i = axis == 1 ? row % ny : row / ny;  // the row's coordinate along `axis`
        const std::size_t start = std::size_t(nx) * row;
        std::fill(sum.begin(), sum.end(), 0.0);
        std::fill(weight.begin(), weight.end(), 0.0);
        for (int t = -reach; t <= reach; ++t) {
          const int q = std::min(std::max(i + t, 0), n - 1);
          const float* src = values.data() + std::ptrdiff_t(start) + (q - i) * stride;
          const double w = taps.w[t + reach];
          for (int x = 0; x < nx; ++x)
            if (std::isfinite(src[x])) sum[x] += w * src[x], weight[x] += w;
        }
        for (int x = 0; x < nx; ++x) {
          const float here = values[start + x];
          out[start + x] = std::isfinite(here) ? float(sum[x] / weight[x]) : here;
        }
      }
    });
    values.swap(out);
  }
  rank_bricks();
  id = next_id++;
}

bool DenseField::straddling_box(float iso, std::array<int, 6>& box) const {
  return brick_index_box(
      *this, [&](std::int64_t b) { return brick_straddles(std::size_t(b), iso); }, box);
}

bool DenseField::surface_bounds(float iso, std::array<double, 6>& box) const {
  // The straddling bricks, grouped 26-connected (union-find over brick numbers).
  const std::size_t nb = std::size_t(bx) * by * bz;
  std::vector<std::int64_t> parent(nb, -1);  // -1: not straddling
  auto root = [&](std::int64_t b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  };
  for (std::size_t b = 0; b < nb; ++b)
    if (brick_straddles(b, iso)) parent[b] = std::int64_t(b);
  for (int c = 0; c < bz; ++c)
    for (int b = 0; b < by; ++b)
      for (int a = 0; a < bx; ++a) {
        const std::int64_t i = a + std::int64_t(bx) * (b + std::int64_t(by) * c);
        if (parent[i] < 0) continue;
        for (int dc = -1; dc <= 0; ++dc)  // the neighbours before it in brick order
          for (int db = -1; db <= 1; ++db)
            for (int da = -1; da <= 1; ++da) {
              const std::int64_t j = i + da + std::int64_t(bx) * (db + std::int64_t(by) * dc);
              if (j >= i || a + da < 0 || a + da >= bx || b + db < 0 || b + db >= by || c + dc < 0)
                continue;
              if (parent[j] >= 0) parent[root(i)] = root(j);
            }
      }
  std::vector<std::uint32_t> count(nb, 0);
  std::uint32_t largest = 0;
  for (std::size_t b = 0; b < nb; ++b)
    if (parent[b] >= 0) largest = std::max(largest, ++count[root(std::int64_t(b))]);
  std::array<int, 6> index_box{};
  const auto kept = [&](std::int64_t b) {
    return parent[b] >= 0 && count[root(b)] >= kSpeckBrickFraction * largest;
  };
  if (!brick_index_box(*this, kept, index_box)) return false;
  box = {1e300, -1e300, 1e300, -1e300, 1e300, -1e300};
  for (int i = 0; i < 8; ++i) {
    std::array<double, 3> q;
    for (int k = 0; k < 3; ++k) q[k] = index_box[2 * k + ((i >> k) & 1)];
    const auto w = world(q);
    for (int c = 0; c < 3; ++c)
      box[2 * c] = std::min(box[2 * c], w[c]), box[2 * c + 1] = std::max(box[2 * c + 1], w[c]);
  }
  return true;
}

std::array<double, 3> DenseField::index(const std::array<double, 3>& p) const {
  std::array<double, 3> q;
  for (int r = 0; r < 3; ++r)
    q[r] = to_index[4 * r] * p[0] + to_index[4 * r + 1] * p[1] + to_index[4 * r + 2] * p[2] +
           to_index[4 * r + 3];
  return q;
}

double DenseField::field(const std::array<double, 3>& p, float iso,
                         std::array<double, 3>* gradient) const {
  const int n[3] = {nx, ny, nz};
  int c0[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double q = std::min(std::max(p[a], 0.0), double(n[a] - 1));
    c0[a] = std::min(int(std::floor(q)), n[a] - 2);
    f[a] = q - c0[a];
  }
  double s[2][2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) s[k][j][i] = signed_at(c0[0] + i, c0[1] + j, c0[2] + k, iso);
  const double fx = f[0], fy = f[1], fz = f[2];
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 = lerp(s[0][0][0], s[0][0][1], fx), x10 = lerp(s[0][1][0], s[0][1][1], fx);
  const double x01 = lerp(s[1][0][0], s[1][0][1], fx), x11 = lerp(s[1][1][0], s[1][1][1], fx);
  const double y0 = lerp(x00, x10, fy), y1 = lerp(x01, x11, fy);
  if (gradient) {
    const double dx00 = s[0][0][1] - s[0][0][0], dx10 = s[0][1][1] - s[0][1][0];
    const double dx01 = s[1][0][1] - s[1][0][0], dx11 = s[1][1][1] - s[1][1][0];
    (*gradient)[0] = lerp(lerp(dx00, dx10, fy), lerp(dx01, dx11, fy), fz);
    (*gradient)[1] = lerp(x10 - x00, x11 - x01, fz);
    (*gradient)[2] = y1 - y0;
  }
  return lerp(y0, y1, fz);
}

std::array<double, 3> DenseField::normal(const std::array<double, 3>& p) const {
  const int n[3] = {nx, ny, nz};
  auto value = [&](int i, int j, int k) { return double(sample(i, j, k)); };
  auto grad_at = [&](const int c[3], double g[3]) {
    for (int a = 0; a < 3; ++a) {
      int hi[3] = {c[0], c[1], c[2]}, lo[3] = {c[0], c[1], c[2]};
      hi[a] = std::min(c[a] + 1, n[a] - 1), lo[a] = std::max(c[a] - 1, 0);
      const int span = hi[a] - lo[a];
      g[a] = span == 0 ? 0.0 : (value(hi[0], hi[1], hi[2]) - value(lo[0], lo[1], lo[2])) / span;
    }
  };
  int c0[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double q = std::min(std::max(p[a], 0.0), double(n[a] - 1));
    c0[a] = int(std::floor(q));
    f[a] = q - c0[a];
  }
  double g[3] = {0, 0, 0};
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const double w = (i ? f[0] : 1 - f[0]) * (j ? f[1] : 1 - f[1]) * (k ? f[2] : 1 - f[2]);
        if (w == 0) continue;
        const int c[3] = {std::min(c0[0] + i, nx - 1), std::min(c0[1] + j, ny - 1),
                          std::min(c0[2] + k, nz - 1)};
        double gc[3];
        grad_at(c, gc);
        for (int a = 0; a < 3; ++a) g[a] += w * gc[a];
      }
  std::array<double, 3> w;
  for (int r = 0; r < 3; ++r)
    w[r] = -sign * (normal_matrix[3 * r] * g[0] + normal_matrix[3 * r + 1] * g[1] +
                    normal_matrix[3 * r + 2] * g[2]);
  const double len = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (!(len > 0) || !std::isfinite(len)) return {0, 0, 0};
  return {w[0] / len, w[1] / len, w[2] / len};
}

}  // namespace isocurv::volume
