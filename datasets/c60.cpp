#include "datasets/c60.h"

#include <cmath>

namespace isocurv::datasets {

std::vector<Eigen::Vector3d> c60_sites(double bond) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const double bases[3][3] = {{0.0, 1.0, 3.0 * phi}, {1.0, 2.0 + phi, 2.0 * phi}, {phi, 2.0, phi * phi * phi}};
  std::vector<Eigen::Vector3d> sites;
  sites.reserve(60);
  for (const auto& b : bases) {
    for (int signs = 0; signs < 8; ++signs) {
      const Eigen::Vector3d v((signs & 1) ? -b[0] : b[0], (signs & 2) ? -b[1] : b[1], (signs & 4) ? -b[2] : b[2]);
      // A zero coordinate with both signs gives the same point: keep the '+' one only.
      bool duplicate = false;
      for (int a = 0; a < 3; ++a) duplicate |= (b[a] == 0.0 && (signs & (1 << a)));
      if (duplicate) continue;
      for (int shift = 0; shift < 3; ++shift)  // cyclic (even) permutations
        sites.emplace_back(0.5 * bond * Eigen::Vector3d(v[shift], v[(shift + 1) % 3], v[(shift + 2) % 3]));
    }
  }
  return sites;
}

}  // namespace isocurv::datasets
