#include "curvature/adaptive_scale.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include <unordered_map>

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

  // E[D^2] - var(D) per vertex, summed per cell; each cell's terms in position order, so that the
  // sums do not depend on the vertices' order (a piece's vertices are ordered differently).
  const double cell = kRegionScales * p.s2;
  auto cell_of = [&](const Vec3f& x) {
    return Cell{std::int64_t(std::floor(x[0] / cell)), std::int64_t(std::floor(x[1] / cell)),
                std::int64_t(std::floor(x[2] / cell))};
  };
  std::unordered_map<Cell, std::vector<std::pair<Vec3f, std::array<double, 2>>>, CellHash> terms;
  for (std::size_t i = 0; i < nv; ++i) {
    if (!(g1[i] > 0) || !(g2[i] > 0) || !std::isfinite(H1[i]) || !std::isfinite(H2[i])) continue;
    const double n1 = h_noise(model, g1[i], p.s1), n2 = h_noise(model, g2[i], p.s2);
    const double d = double(H2[i]) - H1[i];
    const double var = n1 * n1 + n2 * n2 - 2 * rho * n1 * n2;
    terms[cell_of(positions[i])].push_back({positions[i], {d * d - var, var}});
  }
  struct Sum {
    double excess = 0, var = 0;
    std::size_t count = 0;
  };
  std::unordered_map<Cell, Sum, CellHash> sums;
  for (auto& [c, list] : terms) {
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
      return std::tie(a.first[0], a.first[1], a.first[2], a.second) <
             std::tie(b.first[0], b.first[1], b.first[2], b.second);
    });
    Sum s;
    for (const auto& t : list) s.excess += t.second[0], s.var += t.second[1];
    s.count = list.size();
    sums[c] = s;
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
  for (std::size_t i = 0; i < nv; ++i) {
    if (!(g1[i] > 0) || !std::isfinite(g1[i])) continue;
    const auto [cx, cy, cz] = cell_of(positions[i]);
    // Cells in a fixed order: the sum is the same whatever the vertex order.
    double excess = 0, var = 0;
    std::size_t count = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = sums.find(Cell{cx + dx, cy + dy, cz + dz});
          if (it == sums.end()) continue;
          excess += it->second.excess;
          var += it->second.var;
          count += it->second.count;
        }
    // The region's mean excess less kSignificance standard errors: D^2's mean over n independent
    // values (the noise's correlation area 4 pi s1^2 over kVertexArea voxel faces per vertex)
    // has a standard error of mean var(D) sqrt(2 / n).
    double L2 = 0;
    if (count) {
      const double independent = std::max(1.0, double(count) * kVertexArea * face / (4 * M_PI * p.s1 * p.s1));
      const double margin = kSignificance * (var / double(count)) * std::sqrt(2 / independent);
      L2 = std::max(0.0, excess / double(count) - margin) / (half_span * half_span);
    }
    double best = std::numeric_limits<double>::infinity();
    double shape = p.kappa && (*p.kappa)[i] > 0 ? model.shape_scale / (*p.kappa)[i]
                                                 : std::numeric_limits<double>::infinity();
    if (p.limit) shape = std::min(shape, double((*p.limit)[i]));
    for (double s : ladder) {
      if (s > shape && s > ladder.front()) break;
      const double g = g1[i] * std::sqrt((b2 + p.s1 * p.s1) / (b2 + s * s));
      const double n = h_noise(model, g, s), bias2 = 0.25 * s * s * s * s * L2;
      const double e = n * n + bias2;
      if (e < best) best = e, out[i] = float(s);
    }
  }
  return out;
}

}  // namespace isocurv::curvature
