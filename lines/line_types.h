#pragma once
// The kinds of feature line the lines stage extracts, and the --lines list that
// selects them.
// Tested in tests/lines/test_ct_like.cpp, tests/lines/test_ridges.cpp (through its users).
#include <cstdint>
#include <string>

namespace isocurv::lines {

/// A feature line's kind; the value is what the `LineType` cell array holds.
enum class LineType : std::uint8_t {
  contour = 0,    ///< occluding contour: zero set of n.v (view dependent)
  suggestive = 1, ///< suggestive contour: zero set of the radial curvature, D_w
                  ///< k_r > 0 (view dependent)
  ridge = 2,      ///< maximum of k1 along dir1, k1 > |k2| (view independent)
  valley = 3,     ///< minimum of k2 along dir2, k2 < -|k1| (view independent)
};
constexpr int kLineTypeCount = 4;

/// The name used on the command line and in the SVG: contours, suggestive,
/// ridges, valleys.
std::string to_string(LineType t);

/// Which line types to extract.
struct LineSelection {
  bool contours = false, suggestive = false, ridges = false, valleys = false;

  bool has(LineType t) const;
  bool any() const { return contours || suggestive || ridges || valleys; }
  /// The selection as the comma list parse_line_selection accepts.
  std::string to_string() const;
  /// Suggestive contours and ridges/valleys need the curvature derivative
  /// (dcurv).
  bool needs_dcurv() const { return suggestive || ridges || valleys; }
  /// Suggestive contours and ridges/valleys need the principal directions
  /// (dir1, dir2); contours need only the normals.
  bool needs_directions() const { return suggestive || ridges || valleys; }
  /// True when the lines depend on the camera (contours or suggestive
  /// contours).
  bool view_dependent() const { return contours || suggestive; }
};

/// Parses a comma-separated list of contours, suggestive, ridges, valleys (or
/// "all"); each name at most once, none empty. @throw Error naming the bad
/// entry and the choices.
LineSelection parse_line_selection(const std::string &list);

} // namespace isocurv::lines
