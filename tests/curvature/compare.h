#pragma once
// Kernel-versus-reference comparison of two curvature fields of the same mesh.
#include <string>

#include "curvature/curvature_field.h"

namespace isocurv::test {

struct FieldDifference {
  /// RMS differences of k1, k2, H over the RMS of the reference curvedness, of K over the RMS of
  /// its square: relative to the curvature scale, so quantities near zero (H on a minimal
  /// surface) are not divided by their own small size.
  double k1 = 0, k2 = 0, H = 0, K = 0;
  double normal_angle = 0;               ///< largest angle between the normals, radians
  double dir_angle = 0;  ///< largest angle between dir1 lines where k1 - k2 is not tiny, radians
  std::size_t dir_count = 0;             ///< vertices where dir_angle was measured
  double dcurv = 0;      ///< relative RMS difference of dcurv (signs aligned with the directions)
  double area = 0;       ///< relative RMS difference of the areas
  bool same_boundary = true;
  std::string str() const;
};

/// Differences of `x` from `ref`. Directions count where k1 - k2 exceeds `gap` (in 1/length).
FieldDifference compare(const curvature::CurvatureField& x, const curvature::CurvatureField& ref,
                        double gap);

}  // namespace isocurv::test
