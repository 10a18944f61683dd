#pragma once
// Segments joined into polylines where they meet on a mesh edge.
// Tested in tests/lines/test_contours.cpp, tests/lines/test_ct_like.cpp.
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "lines/segments.h"

namespace isocurv::lines {

/// Feature lines as polylines: line i runs through points[offsets[i]] ..
/// points[offsets[i+1]-1] (at least two points; a closed loop repeats its first
/// point at the end).
struct Polylines {
  std::vector<Vec3f> points;
  std::vector<std::uint32_t> offsets{0}; ///< line_count() + 1 entries
  std::vector<LineType> type;            ///< per line
  std::vector<float>
      strength; ///< per line: the length-weighted mean of its segments'

  std::size_t line_count() const { return type.size(); }
  /// Total length (world units) of the lines of `t`.
  double length(LineType t) const;
};

/// Joins segments of the same type that share a mesh edge (Segment::edge_a/b;
/// an edge shared by more than two segments of a type, as on a non-manifold
/// edge, ends the lines there). The result is deterministic: lines start at the
/// earliest unused segment, an open chain from its first end. Segments with a
/// non-finite or coincident endpoint are dropped.
Polylines join_segments(const Segments &segments);

/// The segments for which keep[i] is true, in order (keep has one entry per
/// segment).
Segments select_segments(const Segments &segments,
                         const std::vector<bool> &keep);

} // namespace isocurv::lines
