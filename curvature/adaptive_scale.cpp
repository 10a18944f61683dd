#include "curvature/adaptive_scale.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <unordered_map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/error.h"

namespace isocurv::curvature {

double h_noise(const NoiseModel& model, double gradient, double sigma) {
  if (!(gradient > 0) || !(sigma > 0)) return std::numeric_limits<double>::infinity();
  return kNoiseH * model.noise * std::sqrt(model.cell_volume) / (gradient * std::pow(sigma, 3.5));
}

namespace {

// The median of the positive entries (the whole surface's with a piece); 0 when there are none.
double median_positive(const std::vector<float>& v, const SurfacePiece* piece) {
  std::vector<float> mine;
  mine.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] > 0 && std::isfinite(v[i]) && owns_vertex(piece, i)) mine.push_back(v[i]);
  const std::uint64_t n = total_count(piece, mine.size());
  return n == 0 ? 0.0 : double(kth_smallest_positive(piece, std::move(mine), n / 2));
}

using Cell = std::tuple<std::int64_t, std::int64_t, std::int64_t>;

struct CellHash {
  std::size_t operator()(const Cell& c) const {
    const auto [x, y, z] = c;
    std::uint64_t h = std::uint64_t(x) * 0x9e3779b97f4a7c15ull ^ std::uint64_t(y) * 0xc2b2ae3d27d4eb4full ^
                      std::uint64_t(z) * 0x165667b19e3779f9ull;
    return std::size_t(h ^ (h >> 29));
  }
};

struct RegionSum {
  double excess = 0, var = 0;
  std::size_t count = 0;
};

// Per vertex, the sums of `term` (excess, var; a NaN excess: none) over the vertices in the 27
// cells of side `side` around its own. Each cell's terms are added in position order and the 27
// cells in a fixed order, so that the sums do not depend on the vertices' order (a piece's
// vertices are ordered differently).
std::vector<RegionSum> region_sums(const Positions& positions,
                                   const std::vector<std::array<double, 2>>& term, double side) {
  const std::size_t nv = positions.size();
  auto cell_of = [&](const Vec3f& x) {
    return Cell{std::int64_t(std::floor(x[0] / side)), std::int64_t(std::floor(x[1] / side)),
                std::int64_t(std::floor(x[2] / side))};
  };
  struct Term {
    Cell cell;
    Vec3f x;
    std::array<double, 2> t;
  };
  std::vector<Term> terms;
  terms.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i)
    if (!std::isnan(term[i][0])) terms.push_back({cell_of(positions[i]), positions[i], term[i]});
  tbb::parallel_sort(terms.begin(), terms.end(), [](const Term& a, const Term& b) {
    return std::tie(a.cell, a.x[0], a.x[1], a.x[2], a.t) <
           std::tie(b.cell, b.x[0], b.x[1], b.x[2], b.t);
  });
  std::unordered_map<Cell, RegionSum, CellHash> sums;
  for (std::size_t a = 0, b; a < terms.size(); a = b) {
    RegionSum s;
    for (b = a; b < terms.size() && terms[b].cell == terms[a].cell; ++b)
      s.excess += terms[b].t[0], s.var += terms[b].t[1], ++s.count;
    sums.emplace(terms[a].cell, s);
  }
  std::vector<Cell> own(nv);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const auto& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) own[i] = cell_of(positions[i]);
  });
  std::unordered_map<Cell, RegionSum, CellHash> regions;
  for (const Cell& c : own) {
    if (regions.count(c)) continue;
    const auto [cx, cy, cz] = c;
    RegionSum r;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = sums.find(Cell{cx + dx, cy + dy, cz + dz});
          if (it == sums.end()) continue;
          r.excess += it->second.excess;
          r.var += it->second.var;
          r.count += it->second.count;
        }
    regions.emplace(c, r);
  }
  std::vector<RegionSum> out(nv);
  for (std::size_t i = 0; i < nv; ++i) out[i] = regions.find(own[i])->second;
  return out;
}

}  // namespace

std::vector<float> choose_vertex_scales(const Positions& positions, const NoiseModel& model,
                                        const ScalePilots& p, double lo, double hi,
                                        const SurfacePiece* piece, ScaleChoiceReport* report) {
  const std::size_t nv = positions.size();
  if (!p.H1 || !p.g1 || !p.H2 || !p.g2 || p.H1->size() != nv || p.g1->size() != nv ||
      p.H2->size() != nv || p.g2->size() != nv || (p.kappa && p.kappa->size() != nv) ||
      (p.limit && p.limit->size() != nv))
    throw Error("curvature: the scale choice needs both pilots for every vertex");
  if (!(0 < lo && lo <= p.s1 && p.s1 < p.s2 && p.s2 <= hi) || !std::isfinite(hi))
    throw Error("curvature: the scale choice needs 0 < lo <= s1 < s2 <= hi");
  const std::vector<float>&H1 = *p.H1, &g1 = *p.g1, &H2 = *p.H2, &g2 = *p.g2;
  // The edge's own blur from the median gradients: |g|^-2 grows as b^2 + sigma^2.
  const double m1 = median_positive(g1, piece), m2 = median_positive(g2, piece);
  double b2 = 0;
  if (m1 > m2 && m2 > 0)
    b2 = std::max(0.0, (m2 * m2 * p.s2 * p.s2 - m1 * m1 * p.s1 * p.s1) / (m1 * m1 - m2 * m2));
  if (report) report->blur = std::sqrt(b2);
  const double rho = std::pow(2 * p.s1 * p.s2 / (p.s1 * p.s1 + p.s2 * p.s2), 3.5);
  const double half_span = 0.5 * (p.s2 * p.s2 - p.s1 * p.s1);
  const double face = std::pow(model.cell_volume, 2.0 / 3.0);  // a voxel face, world units^2

  // E[D^2] - var(D) per vertex (NaN where a pilot has no value).
  std::vector<std::array<double, 2>> term(nv, {std::nan(""), 0.0});
  for (std::size_t i = 0; i < nv; ++i) {
    if (!(g1[i] > 0) || !(g2[i] > 0) || !std::isfinite(H1[i]) || !std::isfinite(H2[i])) continue;
    const double n1 = h_noise(model, g1[i], p.s1), n2 = h_noise(model, g2[i], p.s2);
    const double d = double(H2[i]) - H1[i];
    const double var = n1 * n1 + n2 * n2 - 2 * rho * n1 * n2;
    term[i] = {d * d - var, var};
  }
  // The lower confidence bound of L^2 (the region's mean excess less kSignificance standard
  // errors: D^2's mean over n independent values, the noise's correlation area 4 pi s1^2 over
  // kVertexArea voxel faces per vertex, has a standard error of mean var(D) sqrt(2 / n)), in
  // each of two regions around every vertex: the 27 cells of side kRegionScales s2 around its
  // own, and the same of kWideRegion times that side (at most kWideRegionLimit hi), where a bias
  // too small to stand out of one region's noise may stand out of the wider one's.
  std::vector<double> L2(nv, 0.0);
  for (const double side : {kRegionScales * p.s2,
                            std::min(kWideRegion * kRegionScales * p.s2, kWideRegionLimit * hi)}) {
    const std::vector<RegionSum> regions = region_sums(positions, term, side);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const auto& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        const RegionSum& region = regions[i];
        if (!region.count) continue;
        const double count = double(region.count);
        // Each sampled value stands for p.stride vertices' area, and counts once at most.
        const double independent = std::max(
            1.0, std::min(count, count * p.stride * kVertexArea * face / (4 * M_PI * p.s1 * p.s1)));
        const double margin = kSignificance * (region.var / count) * std::sqrt(2 / independent);
        L2[i] = std::max(L2[i], std::max(0.0, region.excess / count - margin) /
                                    (half_span * half_span));
      }
    });
  }

  // The ladder s1 sqrt(2)^j within [lo, hi].
  // Every kLadderSteps-th rung is an exact power of two of s1, so s1 and 2 s1 are rungs to the
  // bit.
  std::vector<double> ladder;
  auto rung = [&](int j) {
    const int e = j >= 0 ? j / kLadderSteps : -((kLadderSteps - 1 - j) / kLadderSteps);
    return std::ldexp(p.s1 * std::pow(2.0, double(j - kLadderSteps * e) / kLadderSteps), e);
  };
  int j = 0;
  while (rung(j - 1) >= lo * (1 - 1e-9)) --j;
  for (; rung(j) <= hi * (1 + 1e-9); ++j) ladder.push_back(rung(j));
  std::vector<float> out(nv, float(p.s1));
  if (model.staircase) {
    // One scale for the whole surface, from its shape: kBinaryShapeScale over the
    // kBinaryCurvatureQuantile of kappa (see NoiseModel::staircase).
    std::vector<float> mine;
    if (p.kappa)
      for (std::size_t i = 0; i < nv; ++i)
        if ((*p.kappa)[i] > 0 && std::isfinite((*p.kappa)[i]) && owns_vertex(piece, i))
          mine.push_back((*p.kappa)[i]);
    const std::uint64_t n = total_count(piece, mine.size());
    double s = hi;
    if (n > 0) {
      const std::uint64_t k = std::min<std::uint64_t>(n - 1, std::uint64_t(kBinaryCurvatureQuantile * double(n)));
      s = model.shape_scale / double(kth_smallest_positive(piece, std::move(mine), k));
    }
    double chosen = ladder.front();
    for (double r : ladder)
      if (r <= s) chosen = r;
    std::fill(out.begin(), out.end(), float(chosen));
    return out;
  }
  // Per rung: N(s) = noise_at[r] / |g(s1)| (the gradient's fall with the blur folded in) and the
  // bias's factor s^4 / 4.
  std::vector<double> noise_at(ladder.size()), bias_at(ladder.size());
  for (std::size_t r = 0; r < ladder.size(); ++r) {
    const double s = ladder[r];
    noise_at[r] = h_noise(model, std::sqrt((b2 + p.s1 * p.s1) / (b2 + s * s)), s);
    bias_at[r] = 0.25 * s * s * s * s;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 2048), [&](const auto& range) {
    for (std::size_t i = range.begin(); i != range.end(); ++i) {
      if (!(g1[i] > 0) || !std::isfinite(g1[i])) continue;
      double best = std::numeric_limits<double>::infinity();
      double shape = p.kappa && (*p.kappa)[i] > 0 ? model.shape_scale / (*p.kappa)[i]
                                                   : std::numeric_limits<double>::infinity();
      if (p.limit) shape = std::min(shape, double((*p.limit)[i]));
      for (std::size_t r = 0; r < ladder.size(); ++r) {
        if (ladder[r] > shape && r > 0) break;
        const double n = noise_at[r] / g1[i];
        const double e = n * n + bias_at[r] * L2[i];
        if (e < best) best = e, out[i] = float(ladder[r]);
      }
    }
  });
  return out;
}

}  // namespace isocurv::curvature
