#pragma once
// Summary statistics of a CurvatureField (stats.json and --json of the isocurv commands).
// Tested in tests/curvature/field_stats_test.cpp.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "core/surface_piece.h"
#include "curvature/curvature_field.h"

namespace isocurv::curvature {

/// The percentiles every Distribution reports.
inline constexpr std::array<double, 7> kStatPercentiles = {1, 5, 25, 50, 75, 95, 99};

/// Area-weighted summary of one per-vertex quantity.
struct Distribution {
  bool empty = true;  ///< no vertex counted: every other member is 0
  double min = 0, max = 0;
  double mean = 0;  ///< sum(w x) / sum(w)
  /// Per kStatPercentiles entry p: the smallest value v such that the vertices with values <= v
  /// carry at least p% of the total weight.
  std::array<double, kStatPercentiles.size()> percentiles{};
};

/// Statistics of H, K, k1 and k2 over the measured, reliable vertices of a field.
struct FieldStats {
  /// Vertices the estimator flagged "Unreliable" (not measured: their values are placeholders,
  /// zero curvature), left out of every Distribution.
  std::size_t unmeasured = 0;
  /// A vertex is unreliable when max(|k1|, |k2|) exceeds this: 1 / (half the mean edge length),
  /// a curvature radius under half an edge, which the mesh cannot resolve (slivers, noise). 0
  /// when no mean edge length was given (then no vertex is unreliable).
  double unreliable_above = 0;
  std::size_t unreliable = 0;  ///< measured vertices over unreliable_above, left out of every Distribution
  std::size_t non_finite = 0;  ///< other vertices with a non-finite k1, k2, H or K, also left out
  std::size_t counted = 0;     ///< vertices in the Distributions (the field's size less the three above)
  bool area_weighted = false;  ///< weights are the Area array (else 1 per vertex: no Area array)
  double weight = 0;           ///< total weight of the counted vertices (their area)
  Distribution H, K, k1, k2;
};

/// The statistics of `field` (arrays of equal length; Area used as the weight when it has one
/// entry per vertex, Unreliable as the unmeasured flag when it has one) with the reliability
/// threshold from `mean_edge_length` (world units).
FieldStats field_stats(const CurvatureField& field, double mean_edge_length);

/// The one rule for which vertices are unmeasured, in the statistics and in the mesh alike: sets
/// `field`'s Unreliable flag (creating the array when absent) on every vertex not already flagged
/// whose k1, k2, H or K is not finite or whose max(|k1|, |k2|) exceeds 2 / (the mean edge length
/// of `mesh`): a radius of curvature under half an edge, which the mesh cannot show. Their values
/// are kept as estimated. With a `piece` (core/surface_piece.h, collective) the mean edge is the
/// whole surface's (over every piece's own triangles). Returns the number of vertices flagged
/// here. curvature::estimate_field applies it to what every estimator gives; field_stats then
/// finds nothing above the threshold that is not flagged.
std::size_t flag_implausible(const Mesh& mesh, CurvatureField& field,
                             const SurfacePiece* piece = nullptr);

/// flag_implausible's bound: 2 / (the mean edge length of `mesh`, over the whole surface with a
/// `piece`: collective), 0 for a mesh without edges (no bound). The fits that sample normal
/// curvatures (quadric, sampling) leave out samples beyond it.
double implausible_above(const Mesh& mesh, const SurfacePiece* piece = nullptr);

/// Per vertex of `field`: 1 where field_stats counts it (measured, finite, within the
/// threshold), else 0. Pictures take their colour range from these vertices.
std::vector<std::uint8_t> counted_vertices(const CurvatureField& field, double mean_edge_length);

}  // namespace isocurv::curvature
