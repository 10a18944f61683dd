#pragma once
// Otsu's threshold on a value histogram: the isovalue that best separates two classes of voxels.
// Tested in tests/volume/test_otsu.cpp.
#include <cstdint>
#include <vector>

namespace isocurv::volume {

/// Otsu's threshold for `histogram` (equal bins over [min, max]): the bin boundary that maximises
/// the between-class variance. When several boundaries tie (e.g. a two-valued 0/255 volume, where
/// every boundary between the two occupied bins is optimal) the middle of the tied run is taken,
/// so binary data gets the midpoint of its two labels. Returns min for an empty histogram or
/// min == max.
double otsu_threshold(const std::vector<std::uint64_t>& histogram, double min, double max);

}  // namespace isocurv::volume
