#pragma once
// Triangle quality of any mesh: smallest area and angle, and the counts of slivers.
// Tested in tests/mc/mesh_check_test.cpp, tests/mc/real_volume_test.cpp.
#include <cstddef>

#include "core/mesh.h"
#include "volume/volume.h"

namespace isocurv::mc {

/// A triangle is "small" when its area is under this fraction of the unit area.
inline constexpr double kSmallAreaFraction = 1e-4;
/// A triangle is "thin" when its smallest angle is under this many degrees.
inline constexpr double kThinAngleDegrees = 1.0;

struct TriangleQuality {
  std::size_t triangles = 0;  ///< triangles measured (those with every index in range)
  double unit_area = 0;       ///< the unit the small-area threshold is relative to
  double min_area = 0;        ///< smallest triangle area, world units^2 (0 without triangles)
  double min_angle = 0;       ///< smallest interior angle of any triangle, degrees
  std::size_t small = 0;      ///< triangles with area < kSmallAreaFraction * unit_area
  std::size_t thin = 0;       ///< triangles with smallest angle < kThinAngleDegrees
};

/// Measures every triangle of `mesh` in double precision. Area = |(b - a) x (c - a)| / 2; angles
/// from atan2(|u x v|, u . v) at each corner, so a triangle with a repeated vertex or collinear
/// corners has angle 0 (and area 0). Triangles with an index out of range are skipped.
/// `unit_area` sets the small-area threshold: for a volume's isosurface use voxel_face_area, for
/// a mesh from elsewhere e.g. the squared mean edge length.
TriangleQuality triangle_quality(const Mesh& mesh, double unit_area);

/// The area of a voxel face in world units: (sx sy sz)^(2/3) for spacing (sx, sy, sz), the
/// geometric mean over the three face orientations of an anisotropic voxel.
double voxel_face_area(const volume::Volume& volume);

}  // namespace isocurv::mc
