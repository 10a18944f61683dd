#pragma once
// The 60 atom sites of the C60 buckyball (an ideal truncated icosahedron), used by the buckyball field.
#include <Eigen/Core>

#include <vector>

namespace isocurv::datasets {

/// Vertices of a truncated icosahedron with every edge (C-C bond) of length `bond`, centred at the
/// origin: the cyclic permutations of (0, +-1, +-3phi), (+-1, +-(2+phi), +-2phi), (+-phi, +-2,
/// +-phi^3), scaled by bond/2. Circumradius = bond/2 * sqrt(9 phi + 10) ~ 2.478 * bond.
std::vector<Eigen::Vector3d> c60_sites(double bond);

}  // namespace isocurv::datasets
