#include "lines/polylines.h"

#include <cmath>
#include <unordered_map>

namespace isocurv::lines {
namespace {

double distance(const Vec3f &a, const Vec3f &b) {
  const double x = double(a[0]) - b[0], y = double(a[1]) - b[1],
               z = double(a[2]) - b[2];
  return std::sqrt(x * x + y * y + z * z);
}

bool finite(const Vec3f &a) {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

// Per (type, edge): the segment ends there, up to two; a third marks the edge
// as a junction.
struct EdgeEnds {
  std::uint32_t end[2] = {0, 0}; // segment * 2 + (0 for a, 1 for b)
  int count = 0;
};

} // namespace

double Polylines::length(LineType t) const {
  double sum = 0;
  for (std::size_t i = 0; i < line_count(); ++i)
    if (type[i] == t)
      for (std::uint32_t j = offsets[i] + 1; j < offsets[i + 1]; ++j)
        sum += distance(points[j - 1], points[j]);
  return sum;
}

Segments select_segments(const Segments &segments,
                         const std::vector<bool> &keep) {
  Segments out;
  for (std::size_t i = 0; i < segments.size() && i < keep.size(); ++i)
    if (keep[i])
      out.push_back(segments[i]);
  return out;
}

Polylines join_segments(const Segments &all) {
  Segments segs;
  segs.reserve(all.size());
  for (const Segment &s : all)
    if (finite(s.a) && finite(s.b) && s.a != s.b)
      segs.push_back(s);
  const std::size_t n = segs.size();
  // Edge keys are per type: a contour and a ridge crossing one edge are not
  // joined.
  auto key = [](std::uint64_t edge, LineType t) {
    return edge * kLineTypeCount + std::uint64_t(t);
  };
  std::unordered_map<std::uint64_t, EdgeEnds> ends;
  ends.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int e = 0; e < 2; ++e) {
      const std::uint64_t edge = e == 0 ? segs[i].edge_a : segs[i].edge_b;
      if (edge == kInsideFace)
        continue;
      EdgeEnds &x = ends[key(edge, segs[i].type)];
      if (x.count < 2)
        x.end[x.count] = std::uint32_t(2 * i + e);
      ++x.count;
    }
  // The end joined to segment end `se` (segment * 2 + side), or -1.
  auto partner = [&](std::uint32_t se) -> long {
    const Segment &s = segs[se / 2];
    const std::uint64_t edge = se % 2 == 0 ? s.edge_a : s.edge_b;
    if (edge == kInsideFace)
      return -1;
    const EdgeEnds &x = ends.at(key(edge, s.type));
    if (x.count != 2)
      return -1;
    return x.end[0] == se ? long(x.end[1]) : long(x.end[0]);
  };
  auto point = [&](std::uint32_t se) {
    return se % 2 == 0 ? segs[se / 2].a : segs[se / 2].b;
  };

  Polylines out;
  std::vector<bool> used(n, false);
  for (std::size_t first = 0; first < n; ++first) {
    if (used[first])
      continue;
    // Walk back from end a to the start of the chain (or once round a loop).
    std::uint32_t start_end =
        std::uint32_t(2 * first); // leaving `first` through its a end
    for (;;) {
      const long p = partner(start_end);
      if (p < 0)
        break;
      const std::uint32_t prev = std::uint32_t(p) / 2;
      if (prev == first || used[prev])
        break;                           // a loop, or an end already taken
      start_end = std::uint32_t(p) ^ 1u; // the previous segment's other end
      // guard against long walks round a loop that does not return to `first`
      if (start_end / 2 == first)
        break;
    }
    // start_end: the free end of the chain's first segment; walk forward from
    // it.
    double weighted = 0, length = 0;
    std::uint32_t se = start_end;
    out.points.push_back(point(se));
    for (;;) {
      const std::uint32_t seg = se / 2;
      used[seg] = true;
      const std::uint32_t other = se ^ 1u;
      out.points.push_back(point(other));
      const double len = distance(segs[seg].a, segs[seg].b);
      weighted += len * segs[seg].strength;
      length += len;
      const long p = partner(other);
      if (p < 0 || used[std::uint32_t(p) / 2])
        break;
      se = std::uint32_t(p);
    }
    out.offsets.push_back(std::uint32_t(out.points.size()));
    out.type.push_back(segs[start_end / 2].type);
    out.strength.push_back(length > 0 ? float(weighted / length)
                                      : segs[start_end / 2].strength);
  }
  return out;
}

} // namespace isocurv::lines
