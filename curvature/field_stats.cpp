#include "curvature/field_stats.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/parallel_invoke.h>

#include "core/mesh_measures.h"

namespace isocurv::curvature {
namespace {

// The weighted distribution of values[i] over the listed vertices.
Distribution distribution(const std::vector<float>& values, const std::vector<std::size_t>& used,
                          const std::vector<double>& weights) {
  Distribution d;
  std::vector<std::pair<float, double>> v;  // (value, weight)
  v.reserve(used.size());
  for (std::size_t i : used) v.emplace_back(values[i], weights[i]);
  if (v.empty()) return d;
  // By value only: the order among equal values changes no percentile (each is a value).
  std::sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  double total = 0, sum = 0;
  for (const auto& [x, w] : v) {
    total += w;
    sum += w * x;
  }
  d.empty = false;
  d.min = v.front().first;
  d.max = v.back().first;
  d.mean = total > 0 ? sum / total : 0;
  std::size_t at = 0;
  double below = v[0].second;  // weight of v[0..at]
  for (std::size_t p = 0; p < kStatPercentiles.size(); ++p) {
    const double want = kStatPercentiles[p] / 100.0 * total;
    while (at + 1 < v.size() && below < want) below += v[++at].second;
    d.percentiles[p] = v[at].first;
  }
  return d;
}

// Why a vertex is left out of the statistics.
enum class Verdict { counted, unmeasured, non_finite, unreliable };

Verdict verdict(const CurvatureField& field, std::size_t i, double unreliable_above) {
  if (field.unreliable.size() == field.size() && field.unreliable[i]) return Verdict::unmeasured;
  if (!std::isfinite(field.k1[i]) || !std::isfinite(field.k2[i]) || !std::isfinite(field.H[i]) ||
      !std::isfinite(field.K[i]))
    return Verdict::non_finite;
  const double k = std::max(std::fabs(field.k1[i]), std::fabs(field.k2[i]));
  if (unreliable_above > 0 && k > unreliable_above) return Verdict::unreliable;
  return Verdict::counted;
}

double threshold(double mean_edge_length) { return mean_edge_length > 0 ? 2.0 / mean_edge_length : 0; }

bool complete(const CurvatureField& field) {
  const std::size_t n = field.size();
  return field.k2.size() == n && field.H.size() == n && field.K.size() == n;
}

}  // namespace

std::vector<std::uint8_t> counted_vertices(const CurvatureField& field, double mean_edge_length) {
  std::vector<std::uint8_t> counted(field.size(), 0);
  if (!complete(field)) return counted;
  const double above = threshold(mean_edge_length);
  for (std::size_t i = 0; i < counted.size(); ++i) counted[i] = verdict(field, i, above) == Verdict::counted;
  return counted;
}

double implausible_above(const Mesh& mesh, const SurfacePiece* piece) {
  // The mean edge over this piece's own triangles, reduced over the pieces in piece order (the
  // same total on every piece): collective.
  auto [sum, count] = edge_length_sum(mesh, piece ? &piece->owned_triangles : nullptr);
  if (piece) {
    const std::vector<double> every = piece->all({sum, count});
    sum = count = 0;
    for (std::size_t i = 0; i + 1 < every.size(); i += 2) sum += every[i], count += every[i + 1];
  }
  return count > 0 ? threshold(sum / count) : 0;
}

std::size_t flag_implausible(const Mesh& mesh, CurvatureField& field, const SurfacePiece* piece) {
  const double above = implausible_above(mesh, piece);  // collective: before anything may return
  const std::size_t n = field.size();
  if (!complete(field) || n != mesh.positions.size()) return 0;
  if (field.unreliable.size() != n) field.unreliable.assign(n, 0);
  std::size_t flagged = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Verdict v = verdict(field, i, above);
    if (v == Verdict::non_finite || v == Verdict::unreliable) field.unreliable[i] = 1, ++flagged;
  }
  return flagged;
}

FieldStats field_stats(const CurvatureField& field, double mean_edge_length) {
  FieldStats s;
  const std::size_t n = field.size();
  s.unreliable_above = threshold(mean_edge_length);
  s.area_weighted = field.area.size() == n;
  std::vector<double> weights(n, 1.0);
  std::vector<std::size_t> used;
  used.reserve(n);
  const bool whole = complete(field);
  for (std::size_t i = 0; i < n && whole; ++i) {
    if (s.area_weighted) weights[i] = std::isfinite(field.area[i]) ? field.area[i] : 0.0;
    switch (verdict(field, i, s.unreliable_above)) {
      case Verdict::unmeasured: ++s.unmeasured; continue;
      case Verdict::non_finite: ++s.non_finite; continue;
      case Verdict::unreliable: ++s.unreliable; continue;
      case Verdict::counted: break;
    }
    used.push_back(i);
    s.weight += weights[i];
  }
  s.counted = used.size();
  if (!whole) return s;
  // Four independent sorts: in parallel (each result is the same as computed alone).
  tbb::parallel_invoke([&] { s.H = distribution(field.H, used, weights); },
                       [&] { s.K = distribution(field.K, used, weights); },
                       [&] { s.k1 = distribution(field.k1, used, weights); },
                       [&] { s.k2 = distribution(field.k2, used, weights); });
  return s;
}

}  // namespace isocurv::curvature
